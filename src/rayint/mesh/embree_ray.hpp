#pragma once
// The Embree ray record both first-hit searches start from (mesh/first_hit.cpp's BoundaryFirstHit
// and mesh/cell_traversal.cpp's CellBoundaryFirstHit), and the frame their single-precision
// geometry lives in. Embree's own header is not included here: only the .cpp files that call
// Embree do.
#include "rayint/geometry/vec3.hpp"

struct RTCRayHit;  // Embree 3's ray-and-hit record (embree3/rtcore_ray.h)

namespace rayint {

// Where Embree's single-precision copy of a mesh lives: the mesh's points moved by -centre (the
// centre of their box) and scaled by a power of two that brings the box diagonal into [1, 2).
// Embree only proposes faces; every decision is taken in double on the mesh's own coordinates.
// Without the frame a float copy loses the mesh: 24 bits at a coordinate 1e6 x the mesh size
// resolve 1/16 of it (a mesh in geographic coordinates), and Embree's products of coordinates
// underflow below ~1e-19 and overflow above ~1e12 (every ray then missed the mesh: the background
// with an error of 0 against a reference that took the same missing segments; issue 33, round 20,
// tests/test_mesh_frames.cpp). Moving is one double subtraction per coordinate, scaling is exact,
// so for a mesh centred at the origin the float copy is the old one times a power of two.
struct LocalFrame {
  Vec3 centre = Vec3::Zero();
  double scale = 1.0;  // a power of two
  // The frame of the points' bounding box [lo, hi] (the traversal's own box; the identity for a
  // zero or non-finite diagonal).
  static LocalFrame of(const Vec3& lo, const Vec3& hi);
  Vec3 point(const Vec3& p) const { return (p - centre) * scale; }
  // A ray parameter along a unit direction (lengths scale; directions do not).
  double length(double t) const { return t * scale; }
};

// Fills Embree's record for one rtcIntersect1 query: the ray origin + t direction in `frame`, in
// single precision, t in [frame.length(max(0, t_near)), t_far], no hit yet. t_far is already in
// the frame (the callers round it differently).
void init_ray_hit(RTCRayHit& rh, const LocalFrame& frame, const Vec3& origin, const Vec3& direction, double t_near,
                  float t_far);

}  // namespace rayint
