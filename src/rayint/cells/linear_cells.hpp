#pragma once
// The linear volume cells of VTK in their own (isoparametric) interpolation: tetra (VTK id 10),
// voxel (11), hexahedron (12), wedge (13), pyramid (14). A cell maps parametric coordinates
// p = (r, s, t) to world points x(p) = sum_i N_i(p) x_i and carries the scalar
// f(p) = sum_i N_i(p) f_i (Williams & Max 1992, appendix, last equation) with the same N_i.
//
// Node order, parametric domain and shape functions are VTK's (Common/DataModel/vtkTetra.cxx,
// vtkVoxel.cxx, vtkHexahedron.cxx, vtkWedge.cxx, vtkPyramid.cxx, InterpolationFunctions and
// InterpolationDerivs), all on [0, 1] coordinates:
//   tetra       N = 1 - r - s - t, r, s, t;                  r, s, t >= 0, r + s + t <= 1
//   voxel       N_i = prod of (1 - u) or u, node i = x fastest, then y, then z (bits of i);
//               [0, 1]^3
//   hexahedron  N0 = (1-r)(1-s)(1-t), N1 = r(1-s)(1-t), N2 = rs(1-t), N3 = (1-r)s(1-t),
//               N4..N7 the same times t instead of (1-t);  [0, 1]^3
//   wedge       N0 = (1-r-s)(1-t), N1 = r(1-t), N2 = s(1-t), N3 = (1-r-s)t, N4 = rt, N5 = st;
//               r, s >= 0, r + s <= 1, t in [0, 1]
//   pyramid     N0..N3 the hexahedron's bottom four, N4 = t (apex); [0, 1]^3 (the whole top
//               face t = 1 collapses onto the apex, where the Jacobian is singular)
// Checked against VTK 9.1 itself (scripts/cells/vtk_shape_fixture.py wrote
// tests/fixtures/cells/vtk_linear_cells.json: vtkCell::EvaluateLocation and
// InterpolateFunctions/InterpolateDerivs at 300 random points of 20 random distorted cells;
// tests [cells][isoparametric]): shape functions and derivatives bit-identical to VTK's, world
// positions within 4.4e-16 (VTK's voxel uses its axis-aligned shortcut there).
//
// Faces: VTK's face node lists (the `Faces` tables of the same sources), in VTK's order; a
// voxel's are listed here in cyclic order (VTK lists them in pixel order, which is not a
// polygon). Triangles are planes, quadrilaterals bilinear patches
//   P(u, v) = (1-u)(1-v) A + u(1-v) B + uv C + (1-u)v D   (A, B, C, D cyclic).
// Face orientation is not used to decide whether a ray enters or leaves: gmsh prisms have the
// opposite Jacobian sign to VTK's documented wedge order (issue 29), and the chord classifies
// the intervals between face hits by locating their midpoints instead (see chord()).
//
// Inverse map (world -> parametric): Newton on x(p) = x_target from a warm start (the cell's
// centre by default), the 3x3 step by Eigen's closed-form (adjugate) inverse. Converged when the
// step is below kNewtonStepTolerance = 4e-15 (parametric units: ~20 ulps of coordinates <= 1)
// or the world residual below 8 eps * the cell's extent; budget kNewtonMaxIterations = 40
// steps, each at most kNewtonMaxStep = 0.5 long (damping for starts far away). A singular
// Jacobian or an exhausted budget is reported as not converged. Both orientations of a cell
// (det J > 0 or < 0) work alike: nothing depends on the sign.
//
// Affine cells: a tetra always, and a voxel, hexahedron, wedge or pyramid whose map has no
// bilinear or trilinear part (a parallelepiped, a prism with parallel congruent triangles, a
// pyramid over a parallelogram ... note VTK's pyramid map is never affine: N4 = t makes the
// apex a collapsed face, so only tetra, voxel, hexahedron and wedge qualify). The non-affine
// coefficient vectors of the map (e.g. x0 - x1 + x2 - x3 for a hexahedron's rs term) are
// compared with kAffineTolerance = 64 eps times the largest node coordinate magnitude: below
// that they are rounding noise of a parallelepiped built from its axes (each node sum of at most
// 4 terms, a few ulps each; 64 leaves a factor 8 margin). An affine cell's inverse map is the
// exact linear inverse, so along a ray the scalar is a polynomial of degree <= 3 in t, computed
// without Newton (cells/cell_integral.hpp routes it accordingly).
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

enum class LinearCellType : int { tetra = 10, voxel = 11, hexahedron = 12, wedge = 13, pyramid = 14 };

inline constexpr int kMaxLinearNodes = 8;
inline constexpr double kNewtonStepTolerance = 4e-15;
inline constexpr int kNewtonMaxIterations = 40;
inline constexpr double kNewtonMaxStep = 0.5;
inline constexpr double kAffineTolerance = 64 * 2.220446049250313e-16;

// The linear type of a VTK id, or false for any other id.
bool linear_cell_type_from_vtk(int vtk_id, LinearCellType& type);
const char* linear_cell_name(LinearCellType type);  // "tetra", "voxel", ... (VTK's names)
int linear_node_count(LinearCellType type);          // 4, 8, 8, 6, 5
int linear_face_count(LinearCellType type);          // 4, 6, 6, 5, 5

// N_i(p) for every node (n = linear_node_count entries written).
void linear_shape_functions(LinearCellType type, const Vec3& p, double* N);
// Derivatives in VTK's layout: dN[i] = dN_i/dr, dN[n + i] = dN_i/ds, dN[2n + i] = dN_i/dt.
void linear_shape_derivatives(LinearCellType type, const Vec3& p, double* dN);
// The nodes in parametric coordinates, VTK order.
const std::vector<Vec3>& linear_reference_nodes(LinearCellType type);
// The parametric centre used as Newton's default start (the centroid of the domain).
Vec3 linear_reference_centre(LinearCellType type);
// Whether p lies in the parametric domain, widened by `slack` on every bounding plane.
bool inside_reference(LinearCellType type, const Vec3& p, double slack = 0.0);

// Face f's nodes (local indices, VTK order; quadrilaterals cyclic). count = 3 or 4.
struct FaceNodes {
  std::array<int, 4> node{};
  int count = 0;
};
FaceNodes linear_face(LinearCellType type, int face);

// A linear cell's map and scalar in the monomials 1, r, s, t, rs, rt, st, rst (every linear
// cell's shape functions are multilinear in p: cells/chord_scalar.hpp describes the form and its
// use): x(p) = sum_m x[m] mono_m(p); f[m] the same for the node values relative to their
// midrange (f[0] is therefore not f's constant term; f[1..7] are f's). Derived by
// make_linear_cell, once per cell (until 2026-12-05 per chord, in ChordScalar's constructor:
// ~3 % of `rayint bench` twisted12).
struct MultilinearForm {
  std::array<Vec3, 8> x{};
  double magnitude = 0.0;  // largest |node coordinate| (Newton's residual scale)
  std::array<double, 8> f{};
  double f_spread = 0.0;   // sum_i |f_i - midrange|: the rounding scale of f[1..7]
};

struct LinearCell {
  LinearCellType type = LinearCellType::hexahedron;
  std::array<Vec3, kMaxLinearNodes> x{};        // node positions, VTK order
  std::array<double, kMaxLinearNodes> value{};  // node scalars
  // Derived by make_linear_cell:
  bool affine = false;
  Eigen::Matrix3d affine_inverse = Eigen::Matrix3d::Identity();  // p = A^-1 (x - x(0)) if affine
  Vec3 affine_origin = Vec3::Zero();                             // x(p = 0)
  double extent = 0.0;                                           // largest node-node distance
  MultilinearForm multilinear;
};

// A cell from n = linear_node_count(type) nodes and values. Throws std::invalid_argument for a
// wrong count, non-finite input or a cell of zero extent. Nothing else is required (distorted,
// non-convex and inverted cells are accepted; their Newton solves report failure when they fail).
LinearCell make_linear_cell(LinearCellType type, const std::vector<Vec3>& nodes,
                            const std::vector<double>& values);

Vec3 cell_position(const LinearCell& cell, const Vec3& p);   // x(p)
double cell_scalar(const LinearCell& cell, const Vec3& p);   // f(p)
Eigen::Matrix3d cell_jacobian(const LinearCell& cell, const Vec3& p);  // columns dx/dr, dx/ds, dx/dt
Vec3 cell_scalar_gradient(const LinearCell& cell, const Vec3& p);     // (df/dr, df/ds, df/dt)

struct InverseMap {
  Vec3 p = Vec3::Zero();  // parametric coordinates
  int iterations = 0;
  bool converged = false;
};
// p with x(p) = world, Newton from `start` (affine cells: the linear inverse, 0 iterations).
InverseMap inverse_map(const LinearCell& cell, const Vec3& world, const Vec3& start);

// The Newton iteration of every isoparametric inverse map (linear cells here, quadratic ones in
// quadratic_isoparametric.hpp), as described at the top of this file: n <= kMaxNewtonNodes
// node positions x, shapes(p, N, dN) fills the n shape functions and their derivatives in VTK's
// layout. A header template so that each cell kind's shape functions are inlined into it.
inline constexpr int kMaxNewtonNodes = 27;
template <class Shapes>
InverseMap newton_inverse_map(const Vec3* x, int n, const Vec3& world, const Vec3& start, Shapes&& shapes) {
  InverseMap out;
  double magnitude = world.cwiseAbs().maxCoeff();
  for (int i = 0; i < n; ++i) magnitude = std::max(magnitude, x[i].cwiseAbs().maxCoeff());
  const double residual_tolerance = 8 * std::numeric_limits<double>::epsilon() * magnitude;
  Vec3 p = start;
  double N[kMaxNewtonNodes], dN[3 * kMaxNewtonNodes];
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    // x(p) and J(p) from one evaluation of the shape functions and their derivatives.
    shapes(p, N, dN);
    Vec3 residual = world;
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int i = 0; i < n; ++i) {
      residual -= N[i] * x[i];
      J.col(0) += dN[i] * x[i];
      J.col(1) += dN[n + i] * x[i];
      J.col(2) += dN[2 * n + i] * x[i];
    }
    if (residual.cwiseAbs().maxCoeff() <= residual_tolerance) {
      out.p = p, out.iterations = it, out.converged = true;
      return out;
    }
    // 3x3 solve by the adjugate (Eigen's closed-form inverse); a singular J gives non-finite steps.
    Vec3 step = J.inverse() * residual;
    if (!step.allFinite()) break;
    const double size = step.cwiseAbs().maxCoeff();
    if (size > kNewtonMaxStep) step *= kNewtonMaxStep / size;
    p += step;
    if (size <= kNewtonStepTolerance) {
      out.p = p, out.iterations = it + 1, out.converged = true;
      return out;
    }
  }
  out.p = p;
  out.iterations = kNewtonMaxIterations;
  out.converged = false;
  return out;
}
InverseMap inverse_map(const LinearCell& cell, const Vec3& world);

// inverse_map's Newton iteration on the cell's multilinear form (the same tolerances, budget and
// step clamp; x and J ~50 flops instead of the shape-function sums): p from its start to the
// solution in place. With `step_first` the residual test is skipped before the first step (a
// start that passes it by a hair still takes one step: chord_scalar.hpp). `steps` counts the
// steps taken. False when it did not converge (p is then not a result).
bool multilinear_newton(const MultilinearForm& m, const Vec3& target, Vec3& p, bool step_first, int& steps);
Eigen::Matrix3d multilinear_jacobian(const MultilinearForm& m, const Vec3& p);

// ---- Ray and faces -------------------------------------------------------------------------

// A canonical order of a face's nodes that depends only on the set of nodes, not on which cell
// lists the face or how: given global ids (distinct) in the cell's cyclic order, the cyclic
// order rotated to start at the smallest id and reflected so that the second is the smaller of
// its two neighbours. Returns the permutation: canonical[k] = cyclic[perm[k]]. Two cells that
// share a face and pass its nodes in this order get bit-identical hits from intersect_face.
std::array<int, 4> canonical_face_order(const std::array<std::int64_t, 4>& global_ids, int count);
// The same with the node coordinates as keys (lexicographic), for callers without global ids.
std::array<int, 4> canonical_face_order(const std::array<Vec3, 4>& coordinates, int count);

struct FaceHit {
  double t = 0.0;        // ray parameter: origin + t direction
  double u = 0.0, v = 0.0;  // face parameters (triangle: barycentrics of nodes 1 and 2)
  double normal_dot_direction = 0.0;  // (dP/du x dP/dv) . direction in the order given
};
struct FaceHits {
  std::array<FaceHit, 2> hit{};
  int count = 0;  // 0, 1 or 2 (two only for a bilinear patch), sorted by t
};
// Every hit of the whole line origin + t direction (any t) with the closed face, nodes in the
// order given (pass them in canonical order for watertightness). Bilinear patch: projecting
// onto two planes through the ray gives two bilinear equations in (u, v); eliminating v leaves
// a u^2 + b u + c = 0, solved by the cancellation-free pair q = -(b + sign(b) sqrt(disc)) / 2,
// u = q / a, u = c / q (a = 0: the linear root; a planar parallelogram); v from whichever of
// the two equations has the larger coefficient; t from the hit point along the direction.
// Accepted when u, v lie in [-kFaceSlack, 1 + kFaceSlack], kFaceSlack = 1e-12 (hits on an
// edge are found from both faces; the chord dedupes them). Triangles: Moller-Trumbore with the
// same slack.
inline constexpr double kFaceSlack = 1e-12;
FaceHits intersect_face(const std::array<Vec3, 4>& nodes, int count, const ViewRay& ray);
// The ray's unit direction and the two planes through it (perpendicular unit vectors), which
// intersect_face would compute for every face: chord() makes them once for a cell's faces.
struct RayFrame {
  Vec3 dir, e0, e1;
  double dn = 0.0;  // |direction|
  explicit RayFrame(const ViewRay& ray);
};
// The same, bit for bit, with the ray's frame given. A bilinear patch lies in the convex hull of
// its corners (slack included: moved by <= 2 kFaceSlack (|B - A| + |D - A| + |A - B + C - D|));
// when all four corners lie beyond that, plus 16 ulps of the projections, on the same side of
// one of the two planes, the face is missed without solving (the roots would fail the u, v test).
FaceHits intersect_face(const std::array<Vec3, 4>& nodes, int count, const ViewRay& ray, const RayFrame& frame);

// The pieces of the line inside the cell: all face hits (every face, nodes put in canonical
// order by coordinates unless `global_ids` are given), sorted; each interval between
// consecutive distinct hits is inside when the inverse map of its midpoint converges into the
// domain (slack 1e-9). Adjacent inside intervals are merged. Intervals are over all t; the
// caller clips to t >= 0. `failed` is set when an inverse map of a midpoint did not converge.
struct ChordInterval {
  double t_near = 0.0, t_far = 0.0;  // t_near < t_far
  // The parametric point at the midpoint of the interval's first stretch (the classification's
  // Newton solve): a warm start for the integral's inverse maps (cell_integral.hpp); NaN if none.
  Vec3 p_mid = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
};
struct ChordFaceHit {
  double t = 0.0;
  int face = 0;  // local face index (linear_face)
};
struct Chord {
  std::vector<ChordInterval> intervals;  // sorted by t
  std::vector<ChordFaceHit> hits;        // every face hit, sorted by (t, face): which faces an
                                         // interval ends on (mesh traversal, mesh/cell_traversal.hpp)
  bool failed = false;
};
Chord chord(const LinearCell& cell, const ViewRay& ray, const std::int64_t* global_ids = nullptr);
// chord()'s classification, for callers that find the face hits themselves (mesh/cell_traversal):
// ts[0..n_ts) the sorted distinct hit parameters; writes the inside intervals (merged, at most
// n_ts - 1) to out and returns how many; sets `failed` when a midpoint's inverse map did not converge.
int classify_chord_intervals(const LinearCell& cell, const ViewRay& ray, const double* ts, int n_ts, ChordInterval* out,
                             bool& failed);

}  // namespace rayint
