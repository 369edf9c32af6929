#pragma once
// Axis-aligned boxes and where a viewing ray runs inside one: the single ray/box clip of the
// library (scene media, voxel grids and the multiple-scattering volumes all clip with it).
//
// Slab method (Kay & Kajiya 1986), restricted to t >= 0 (in front of the eye): per axis the ray
// parameters of the two planes, t_enter the largest entry and t_exit the smallest exit. A
// direction component of 0 leaves that axis unrestricted when the origin lies within it (a ray in
// a boundary plane counts as inside). Components of a box may be infinite (a slab is infinite in
// x and y). The arithmetic is two divisions per axis and nothing else, so t_enter and t_exit are
// within 1 ulp of the plane crossings (tests/test_voxel_grid.cpp checks the chords to 2e-15 of
// the box diagonal).
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

// [t_enter, t_exit] of a ray parameter t (point = origin + t * direction), t_enter >= 0.
struct RaySpan {
  double t_enter = 0.0;
  double t_exit = 0.0;
  bool hit = false;  // false: the ray misses (t_enter, t_exit are then 0)
  double length() const { return hit ? t_exit - t_enter : 0.0; }
};

// An axis-aligned box [lower, upper]; components may be infinite.
struct Bounds {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Ones();
  bool contains(const Vec3& p) const;  // closed box
  bool finite() const;
  // Where `ray` is inside the closed box for t >= 0 (slab method, see above). hit == false when
  // the intersection is empty, a single point, or unbounded.
  RaySpan clip(const ViewRay& ray) const;
};

// The smallest box holding every point (componentwise min and max, exact); the zero box for no
// points. The mesh checks and both traversals take their bounding box from here.
Bounds point_bounds(const std::vector<Vec3>& points);

// The same slabs against [lower - pad, upper + pad], NOT restricted to t >= 0: {t0, t1} with t0
// negative when the origin is inside, and t1 < max(t0, 0) (or -1) when the ray misses. The mesh
// traversals start their walk just before t0 and stop just after t1 (mesh_walk_start).
struct SlabInterval {
  double t0;
  double t1;
};
SlabInterval padded_slab_interval(const Vec3& lower, const Vec3& upper, double pad, const Vec3& origin,
                                  const Vec3& direction);

// Where the mesh traversals (mesh/tet_traversal.hpp, mesh/cell_traversal.hpp) walk a viewing ray
// through a mesh whose bounding box is [lower, upper] with diagonal `diagonal`: the direction
// made unit (kept as given when its norm is 0 or not finite), the ray clipped against the box
// padded by 1e-6 diagonal (+1e-300, for a box of one point), and the walk's origin put 0.01
// diagonal before the padded entry, so that the walk starts just outside the box. Every t is
// measured from that origin.
struct MeshWalkStart {
  Vec3 direction;       // unit
  Vec3 origin;          // the walk's origin; the ray's own origin when `empty`
  double t_eye = 0.0;   // where the eye is: > 0 when it is inside the box (clip there); 0 when `empty`
  double t_end = 0.0;   // just past the padded box's exit (0.01 diagonal beyond it)
  bool empty = true;    // no walk: the ray misses the box, the box is behind the eye, or d = 0
};
MeshWalkStart mesh_walk_start(const ViewRay& ray, const Vec3& lower, const Vec3& upper, double diagonal);

}  // namespace rayint
