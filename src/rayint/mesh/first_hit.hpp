#pragma once
// First hit of a ray on the boundary of a tetrahedral mesh: Embree 3 (Debian's libembree-dev)
// over the boundary faces, in its robust (watertight) mode.
//
// Embree intersects in single precision, so it only proposes a face; the decision is taken in
// double precision by the caller's filter (TetTraversal passes one that recomputes the crossing
// parameter from the face's own plane and accepts only entering faces at or beyond a bound).
// Consequence, documented in cases/README.md: whether a ray that passes within ~1e-7 x the mesh
// size of a boundary edge of the mesh's silhouette hits the adjacent face or not is decided in
// single precision. Embree's copy of the points is in the mesh's LocalFrame (embree_ray.hpp), so
// that holds wherever the mesh lies and whatever its size.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

class BoundaryFirstHit {
 public:
  // Accepts or rejects a proposed boundary face (index into the faces given to the constructor).
  using Filter = bool (*)(const void* user, std::uint32_t face);

  // points: all mesh points; faces: boundary triangles as point indices; [box_min, box_max]: the
  // points' bounding box (Embree's LocalFrame is formed from it).
  BoundaryFirstHit(const std::vector<Vec3>& points, const std::vector<std::array<std::int32_t, 3>>& faces,
                   const Vec3& box_min, const Vec3& box_max);
  ~BoundaryFirstHit();
  BoundaryFirstHit(const BoundaryFirstHit&) = delete;
  BoundaryFirstHit& operator=(const BoundaryFirstHit&) = delete;

  // The closest face with Embree parameter in [t_near, t_far] that `filter` accepts; -1 if none.
  // Thread-safe.
  std::int64_t first(const Vec3& origin, const Vec3& direction, double t_near, double t_far,
                     Filter filter, const void* user) const;
  // The same for up to kPacket rays at once (Embree's 8-wide packet traversal over coherent rays,
  // e.g. neighbouring pixels): ray i has origins[i], directions[i], t_near[i], t_far[i] and
  // filter user users[i]; active[i] false skips it (result -1). result[i] is what first() gives
  // for ray i, up to which of two faces Embree takes where both are hit at the same single-precision
  // t (an edge): its packet and single-ray kernels are the same watertight test.
  static constexpr int kPacket = 8;
  void first_packet(const Vec3* origins, const Vec3* directions, const double* t_near, const double* t_far,
                    const bool* active, int n, Filter filter, const void* const* users, std::int64_t* result) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rayint
