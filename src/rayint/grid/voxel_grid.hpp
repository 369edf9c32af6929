#pragma once
// Voxel grids: scalars on the points of a regular grid, and what a viewing ray sees of them.
//
// Two interpolants of the same point values are offered, because the issue asks how far apart
// they are:
//  * trilinear (sample(), trilinear_pieces()): inside one cube the scalar is
//    f(u, v, w) = sum_{a,b,c in {0,1}} f_abc u^a (1-u)^(1-a) ... (Williams & Max 1992, appendix,
//    the 8-node brick); along a straight ray u, v, w are linear in t, so f is a cubic in t
//    (the uvw term), and the closed form of Sec. 3.3 does not apply;
//  * piecewise linear on the Freudenthal/Kuhn decomposition of every cube into 6 tetrahedra
//    around its main diagonal (kuhn_value(), ray_segments()): inside each tetrahedron the scalar
//    is linear (Eq. 9), so along the ray it is linear between breakpoints (Eq. 13) and the exact
//    method applies unchanged.
//
// Why Kuhn and not the alternating 5-tet split: the Kuhn tetrahedra of all cubes together are
// the cells of the hyperplane arrangement {x_i = k} and {x_i - x_j = k} (i < j, k integer, in
// grid index coordinates x). The same 6 tets are used in every cube (no parity to track), faces
// match between neighbours by construction (the face of a cube is split along the same face
// diagonal from both sides), and the breakpoints along a ray are just the crossings of those
// planes: no cell walk, no face tests, nothing that can fail for rays through edges or vertices
// or lying in a grid plane (a plane parallel to the ray has no crossing; the interpolant is
// continuous, so a point on a face may be evaluated from either side). The 5-tet split has
// fewer tets but its face diagonals alternate with the cube's parity, so its breakpoints are
// not a fixed plane arrangement. Kuhn's tets are not congruent-regular (one edge is the cube
// diagonal) and the interpolant is not symmetric under reflections of the grid; both are
// irrelevant for the measurements here.
//
// Accuracy (tests/test_voxel_grid.cpp, [grid]): segment endpoints and the scalars at them are
// computed in double from the plane crossings. The summed segment lengths match the analytic box
// chord to <= 2.0e-15 of the box diagonal (400 random face-to-face rays at > 3 degrees to their
// faces; rays in grid planes, along grid lines, through vertices: within 1e-14 relative); the
// Kuhn interpolant deviates from linear inside a segment by <= 1.3e-14 (values O(1)); the
// trilinear cubics match sample() to <= 5.6e-15. A crossing at a grazing angle theta moves by
// ~eps |coordinate| / sin(theta): that is the conditioning of the ray, not of this code.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "rayint/geometry/bounds.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/model/poly_ray.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

// Where a grid's own frame sits in the world (VTK 9 ImageData's Direction): a point p of the
// grid's axis-aligned frame (origin(), spacing(): every VoxelGrid function works there) is at
// pivot + direction (p - pivot) in the world, i.e. world = Origin + Direction (index * spacing)
// with pivot the image's Origin. The identity unless a reader set it; scene/grid_field.hpp
// applies it, VoxelGrid's own functions ignore it.
struct GridPlacement {
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  // orthonormal: a rotation or reflection
  Vec3 pivot = Vec3::Zero();
  bool identity() const { return direction == Eigen::Matrix3d::Identity(); }
};

// Empty when `direction` is finite and orthonormal to 1e-12 (|D^T D - I| entrywise: a VTK
// Direction written from a rotation holds it to a few ulps, and the transpose then inverts it to
// that accuracy); else what is wrong, for a reader's message.
std::string check_direction(const Eigen::Matrix3d& direction);

class VoxelGrid {
 public:
  VoxelGrid() = default;
  // dims: points per axis (each >= 2); spacing > 0 per axis; values in x-fastest order,
  // index = i + nx * (j + ny * k), size nx * ny * nz. Throws std::invalid_argument otherwise.
  VoxelGrid(std::array<int, 3> dims, Vec3 origin, Vec3 spacing, std::vector<double> values);

  const std::array<int, 3>& dims() const { return dims_; }
  const Vec3& origin() const { return origin_; }
  const Vec3& spacing() const { return spacing_; }
  const std::vector<double>& values() const { return values_; }
  Vec3 lower() const { return origin_; }  // world bounds
  Vec3 upper() const;
  std::size_t point_count() const { return values_.size(); }
  double value(int i, int j, int k) const {
    return values_[static_cast<std::size_t>(i) +
                   static_cast<std::size_t>(dims_[0]) *
                       (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_[1]) *
                                                          static_cast<std::size_t>(k))];
  }

  // Trilinear interpolation at a world point. Points outside the box are clamped to it (the
  // value on the nearest boundary point), so a renderer stepping slightly past a face reads the
  // face value.
  double sample(const Vec3& p) const;
  // The piecewise linear (Kuhn, 6 tets per cube) interpolant at a world point; clamped likewise.
  double kuhn_value(const Vec3& p) const;

  // Blanked (hidden) cubes, as VTK's vtkImageData blanks cells (vtkGhostType: a cell is not
  // visible when it is flagged HIDDENCELL or any of its 8 points HIDDENPOINT; vtkImageData::
  // IsCellVisible, checked on VTK 9.1). A hidden cube is EMPTY: no absorption, no emission, the
  // light passes it unchanged; its point values are never read by the ray integrals. The mask is
  // one byte per cube, index i + (nx-1) * (j + (ny-1) * k), non-zero = hidden; an empty mask (the
  // default) hides nothing. Throws std::invalid_argument for a mask of the wrong size.
  // Honoured by trilinear_cubics / trilinear_pieces / trilinear_ray and ray_segments (and so by
  // every integral built on them); sample() and kuhn_value() ignore it (a value cannot say
  // "empty"): callers that sample a blanked grid must check cube_hidden() themselves.
  void set_hidden_cubes(std::vector<unsigned char> hidden);
  bool has_hidden_cubes() const { return !hidden_.empty(); }
  std::size_t hidden_cube_count() const;
  bool cube_hidden(int i, int j, int k) const {
    return !hidden_.empty() &&
           hidden_[static_cast<std::size_t>(i) +
                   static_cast<std::size_t>(dims_[0] - 1) *
                       (static_cast<std::size_t>(j) +
                        static_cast<std::size_t>(dims_[1] - 1) * static_cast<std::size_t>(k))] != 0;
  }

  Bounds bounds() const { return {lower(), upper()}; }
  const GridPlacement& placement() const { return placement_; }
  // Throws std::invalid_argument unless check_direction(p.direction) is empty and pivot finite.
  void set_placement(const GridPlacement& p);
  // Where the ray is inside the closed box, t >= 0: bounds().clip(ray) (geometry/bounds.hpp).
  RaySpan clip(const ViewRay& ray) const { return bounds().clip(ray); }

 private:
  std::array<int, 3> dims_{{2, 2, 2}};
  Vec3 origin_ = Vec3::Zero();
  Vec3 spacing_ = Vec3::Ones();
  std::vector<double> values_ = std::vector<double>(8, 0.0);
  GridPlacement placement_;
  std::vector<unsigned char> hidden_;  // per cube; empty: none hidden
};

// The segments of the Kuhn interpolant along `ray` inside the grid, far -> near as model/ray.hpp
// orders them, each with its world length (|direction| need not be 1) and the scalars at its
// ends; `background` is what enters at the far end. A ray that misses gives no segments.
// Segments inside hidden cubes (VoxelGrid::cube_hidden) are left out: they are empty, and a ray
// of segments integrates each on its own, so leaving one out is exactly "no absorption, no
// emission there" (the Kuhn planes include the cube faces, so every segment lies in one cube).
// Breakpoints are never merged (merging would put a kink inside a segment): planes crossing at
// one point (a ray through an edge or vertex) give equal t values, kept once; nearly equal ones
// give very short segments, which cost a piece each and contribute their (tiny) share exactly.
Ray ray_segments(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background = Rgb{});
// The same restricted to t in `within` (e.g. the part of the ray inside a cell whose faces are
// planes of the Kuhn arrangement, as cells/cell.cpp uses it); within.hit == false gives none.
Ray ray_segments(const VoxelGrid& grid, const ViewRay& ray, const RaySpan& within,
                 const Rgb& background);

// One cube of the trilinear interpolant along a ray: the scalar is the cubic
// f(s) = c[0] + c[1] s + c[2] s^2 + c[3] s^3 in the distance s from the far end of the piece
// (s in [0, length], toward the eye), so that the pieces read like model/poly_ray.hpp.
struct TrilinearPiece {
  std::array<int, 3> cube{};  // lower-corner point index of the cube
  double t_far = 0.0;         // ray parameters of the piece's ends (t_far > t_near)
  double t_near = 0.0;
  PolySegment segment;        // length and the 4 coefficients in s
};

// The cubes the ray crosses inside the grid, far -> near, with the cubic of each; hidden cubes
// (VoxelGrid::cube_hidden) are left out (empty: the light passes them unchanged), so with a
// blanked grid consecutive pieces need not share their ends.
std::vector<TrilinearPiece> trilinear_pieces(const VoxelGrid& grid, const ViewRay& ray);

// The same in fixed storage, for loops over many rays: `out` is cleared and refilled, `scratch`
// holds the crossings (both reused across calls, so a warmed-up caller allocates nothing).
// The cube walk is the crossings of the planes x_i = k in index coordinates, each axis's
// sequence in order and the three merged (a 3D DDA): consecutive pieces share their end t
// exactly, from clip's t_enter to t_exit, so no length is dropped or counted twice; a ray
// through an edge or vertex crosses two or three planes at one t, kept once (bit-equal t) or
// as a piece of a few ulps (its share exact); a ray in a grid plane (direction component 0)
// crosses none of that axis's planes and reads the cube chosen at each piece's midpoint.
struct TrilinearCubic {
  std::array<int, 3> cube{};
  double t_far = 0.0, t_near = 0.0;
  double length = 0.0;                 // world length
  std::array<double, 4> coeffs{};      // scalar in s, distance from the far end
};
void trilinear_cubics(const VoxelGrid& grid, const ViewRay& ray, std::vector<TrilinearCubic>& out,
                      std::vector<double>& scratch);
// The trilinear weight of each of the piece's cube's 8 corners along the ray, as a cubic in the
// same s as the piece's coefficients (corner c: bit i set = upper side on axis i): the piece's
// cubic is sum_c value(corner c) * weight_c, computed by trilinear_cubics from these same cubics
// (so d coeffs / d value(corner c) = weight_c exactly as the walk uses it). For gradients.
std::array<std::array<double, 4>, 8> trilinear_corner_cubics(const VoxelGrid& grid, const ViewRay& ray,
                                                             const TrilinearCubic& piece);
// Index into values() of corner c of `cube`.
std::size_t trilinear_corner_index(const VoxelGrid& grid, const std::array<int, 3>& cube, int corner);
// The same as a PolyRay for the polynomial reference (reference/poly_reference.hpp).
PolyRay trilinear_ray(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background = Rgb{});

}  // namespace rayint
