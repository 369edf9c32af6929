#pragma once
// The Embree ray record both first-hit searches start from (mesh/first_hit.cpp's BoundaryFirstHit
// and mesh/cell_traversal.cpp's CellBoundaryFirstHit). Embree's own header is not included here:
// only the .cpp files that call Embree do.
#include "rayint/geometry/vec3.hpp"

struct RTCRayHit;  // Embree 3's ray-and-hit record (embree3/rtcore_ray.h)

namespace rayint {

// Fills Embree's record for one rtcIntersect1 query: the ray origin + t direction in single
// precision, t in [max(0, t_near), t_far], no hit yet.
void init_ray_hit(RTCRayHit& rh, const Vec3& origin, const Vec3& direction, double t_near, float t_far);

}  // namespace rayint
