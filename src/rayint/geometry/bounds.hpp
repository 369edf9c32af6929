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

}  // namespace rayint
