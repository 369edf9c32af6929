#pragma once
// Exact gradients of a mesh render (issue 28, meshes): the derivative of a pixel's intensity with
// respect to every vertex scalar (the sparse Jacobian a tetrahedral renderer's adjoint produces)
// and every vertex position, and the gradient of an image loss with respect to them.
//
// Chain rule through the traversal (mesh/tet_traversal.hpp). A pixel's ray is the segments of its
// crossings; exact_ray_gradient (integrators/exact_grad.hpp) gives dI/dL, dI/ds_far and
// dI/ds_exit of every segment. Each segment end is a point p of its cell at ray parameter t:
//   * scalars: s(p) = sum_k lambda_k(p) v_k over the cell's four vertices (the cell's Eq. 9
//     field is that interpolation), so dI/dv_k += dI/ds . lambda_k. Positions are held fixed,
//     so this holds at every point, including rays through vertices and along edges.
//   * positions, at a face crossing (the end lies on the face a, b, c opposite the vertex whose
//     lambda is ~0): p = o + t d = lambda_a a + u b + v c, lambda_a = 1 - u - v. Differentiating
//     this identity, M d(t, u, v) = lambda_k dx_k for a move dx_k of face vertex k, with
//     M = [d, -(b - a), -(c - a)]. With r = (dI/dt, dI/ds (s_b - s_a), dI/ds (s_c - s_a)),
//     dI/dx_k = lambda_k M^{-T} r. dI/dt is +dI/dL at a segment's far end (t_out) and -dI/dL at
//     its exit (t_in). The fourth vertex does not move the crossing or its scalar.
//   * positions, at the eye inside a cell (the end is not on a face: every lambda > kOnFace):
//     t is fixed; s(p) at fixed p moves as dI/dx_k = -dI/ds . lambda_k grad s (grad s: the cell's
//     constant gradient).
//   * cell data (one scalar per tet, TetMesh::cell_scalars): s is the cell's value at both ends;
//     dI/d value_cell = dI/ds_far + dI/ds_exit, and positions enter through t alone.
// Where positions are not differentiable: an end on an edge or a vertex of the mesh (two or more
// lambdas ~0) -- moving a vertex changes which cells the ray crosses, and the one-sided
// derivatives differ in general. There the face opposite the smallest lambda is used and the end
// is counted (`ends_on_edges`): a caller that needs a defined position gradient checks it is 0.
// Scalar derivatives are defined there (positions fixed).
// Jumps of the transfer functions (model/ray_gradient.hpp): the crossing term of a jump inside a
// cell is in exact_ray_gradient's dI/ds_far, dI/ds_exit (and its length derivative is 0), so the
// chain above carries it to vertex scalars and positions unchanged. Where the ray's scalar is
// exactly on a jump at a segment end, that end's dI/ds is NaN (no derivative): the pixel's
// `undefined` says why and the NaN reaches the entries it touches; the image loss counts such a
// pixel as failed (pixels_failed).
//
// Accuracy (tests/test_mesh_gradient.cpp, [grad]): against fourth-order central differences of
// the 50-digit reference render (reference_ray on the retraced, perturbed mesh), relative to the
// largest |entry| of the pixel's channel: scalars <= 1e-9 and positions <= 1e-8 measured in the
// test (the differences' own noise: traversal rounding ~1e-16 / step 1e-4 .. 1e-3), see the test
// for the measured figures.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/model/ray.hpp"
#include "rayint/render/image.hpp"

namespace rayint {

// lambda below this (relative to 1) counts as 0: the end is on that face. Traversal puts an end
// on its face to rounding (~1e-15 of the cell's size); 1e-9 leaves room for slivers.
inline constexpr double kOnFace = 1e-9;

// One pixel's derivatives, sparse: the vertices (or cells, for cell data) that its crossings
// touch, in increasing index order.
struct PixelJacobian {
  Rgb intensity{};                            // exact (exact_ray_gradient's forward value)
  bool cell_scalars = false;                  // true: `index` are tets (cell data), else points
  std::vector<std::int32_t> index;            // vertices (or cells) with a non-zero derivative
  std::vector<Rgb> d_scalar;                  // [i][c] dI_c / d scalar of index[i]
  std::vector<std::int32_t> position_index;   // vertices whose position moves the pixel
  std::vector<std::array<Rgb, 3>> d_position; // [i][axis][c] dI_c / d x_axis of position_index[i]
  long ends_on_edges = 0;                     // segment ends on an edge/vertex (positions undefined)
  std::string undefined;                      // empty, or why some entries are NaN (a jump: see above)
  double channel_scale(int c) const;          // largest |entry| of channel c (scalars and positions)
};

// The Jacobian of the pixel seen along `view` (background entering at the far end). Shading is
// not differentiated (surface_shading is not part of the ray); callers refuse shaded cases.
PixelJacobian pixel_jacobian(const TetTraversal& mesh, const TransferFunctions& tf,
                             const ViewRay& view, const Rgb& background);

// The loss sum over pixels and channels of (I - target)^2 of the camera image of `mesh_case`,
// and its gradient with respect to every vertex scalar (one per point, or per tet for cell data)
// and every vertex position ([point][axis]). Threads over rows (core/parallel.hpp).
struct LossGradient {
  Image image;                                 // the exact render
  double loss = 0.0;
  bool cell_scalars = false;
  std::vector<double> d_scalar;                // dloss / d scalar, per point (or per tet)
  std::vector<std::array<double, 3>> d_position;  // dloss / d position, per point (empty: not asked)
  long ends_on_edges = 0;                      // summed over pixels (positions undefined there; 0
                                               // when positions are not asked for)
  long pixels_failed = 0;                      // pixels whose intensity or gradient is not finite
                                               // (or undefined: the ray's scalar on a jump)
};
// `target` must have the camera's size (std::invalid_argument otherwise); mesh_case.camera must be
// set and its shading off. positions = false skips the position gradient (cheaper).
LossGradient image_loss_gradient(const MeshCase& mesh_case, const TetTraversal& mesh,
                                 const Image& target, unsigned threads = 0, bool positions = true);

}  // namespace rayint
