#pragma once
// The emission-absorption integral (Williams & Max 1992, Eq. 4: L = int kappa rho exp(-int rho))
// along a chord [t_near, t_far] of a ray inside one linear VTK cell (cells/linear_cells.hpp),
// with the scalar the cell's own interpolant f(t) = sum_i N_i(p(t)) f_i, p(t) the inverse map of
// the ray point. The transfer functions are the six piecewise-linear functions of Sec. 3.1
// (model/transfer_function.hpp), per channel, as the exact integrator uses them.
//
// Paths (CellPieceIntegral::path says which was taken):
//   linear_exact   tetra: the scalar is linear in t; the chord is one Segment split at the
//                  breakpoints (model/pieces.hpp) and each piece integrated in closed form by
//                  exact_piece (integrators/exact.hpp; measured 8.05e-14 relative worst there).
//   polynomial     an affine voxel, hexahedron or wedge (linear_cells.hpp, kAffineTolerance):
//                  p(t) is the exact linear inverse, so f(t) is a polynomial of degree <= 3 in t;
//                  its 4 Chebyshev coefficients on the chord are multiplied out in the nodal
//                  form (chord_scalar.hpp affine_chord_chebyshev: each N_i(p(t)) a product of
//                  linear factors, f_i taken relative to their midrange), no samples, no Newton
//                  solves; e_f is their rounding scale (8 eps x the same sums over absolute
//                  values). Until 2026-12-05 f was sampled at 9 Chebyshev-Lobatto points and the
//                  coefficients above 3 dropped (their sum the tail): the expansion is ~15 %
//                  faster on `rayint bench` box12, ~4x per chord in tools/cell_accuracy, with
//                  voxel_box's errors moved at the rounding level, both ways (reports/cells/bench.md,
//                  "Planar faces, clipped affine cells").
//                  (5 samples, degree 4, measured 2026-12-05: 7 % faster on BM_mesh/own_box, but
//                  the accuracy tool's voxel_box worst absolute error 5.11e-15 -> 5.63e-15 and
//                  median relative 7.77e-16 -> 8.13e-16: the 9-point projection averages the
//                  samples' rounding. Not taken.)
//   isoparametric  any other cell: f(t) sampled at the Chebyshev-Lobatto points of [t_near,
//                  t_far] through inverse maps (cells/chord_scalar.hpp: the cell's multilinear
//                  form, Newton started from a Taylor expansion of p(t) about the interval's
//                  centre, accepted by inverse_map's own residual test, then one polishing step).
//                  Hexahedra and voxels first try f's own Taylor series about the chord's centre
//                  (chord_scalar.hpp "f's own series"): where it converged and its truncation
//                  is <= eps max|f_i| / 4 (kSeriesTruncation), its Chebyshev coefficients with their rounding bound as
//                  e_f replace step 1's samples (no Newton solve per sample, no DCT).
// Quadratic cells (cells/quadratic_isoparametric.hpp: tet10, hex20, wedge15, curved too) take the
// isoparametric path with their own inverse map, or the polynomial path when affine (a
// straight-edged tet10: f is a quadratic in t); the steps below are the same code
// (integrate_sampled). Measured against the 50-digit reference (ids 24-26): worst relative error
// 6.8e-15 over 18 chords of random curved cells (tests [cells][quadratic]), 1.1e-14 over 186
// chords of gmsh's and VTK's files (tests [quadratic][mesh][reference]).
// Both curved paths then do:
//   1. Chebyshev interpolant of f on the chord, degree n = 8, 16, 32, 64 (nested points, values
//      reused) until the last two coefficients are below kChebyshevTail = 64 eps * max|f_i|
//      (rounding noise of f is ~eps max|f_i|); otherwise the interval is halved (depth
//      budget kMaxBisections = 6) and each half interpolated alone. The tail (|c_{n-1}| + |c_n|)
//      is kept as the interpolant's error estimate e_f. Below degree kTrustedDegree = 16 the
//      two-coefficient test alone is not trusted: a hexahedron's or voxel's degree 8 is accepted
//      only when the Taylor series of f about the chord's centre (chord_scalar.hpp taylor_tail)
//      bounds the coefficients above 8 by half the target, and twice that bound joins e_f
//      (wedges, pyramids and quadratic cells start at 16, affine quadratic ones at 8, as before). Trailing coefficients whose absolute
//      sum is <= kChopFraction = 1/64 of the tail target (so <= eps max|f_i|) are then dropped
//      and their sum added to e_f (|T_k| <= 1); where the Taylor bound of f's part above a
//      degree m is below that same fraction, the coefficients above m are dropped too (they are
//      the samples' rounding, ~eps |f| each, spread by the DCT) and the bound joins e_f. A nearly
//      cubic f then costs a short Clenshaw sum.
//   2. Critical points: none when |c_1| > sum_{k>=2} k^2 |c_k| (|T_k'| <= k^2 on [-1, 1]: f' keeps
//      the sign of c_1, a proof, no search); otherwise sign changes of f' at M + 1 points (M the
//      power of two >= max(8, 2n)), refined by TOMS 748 on the
//      interpolant's derivative; between them f is monotone. Breakpoint crossings: every
//      breakpoint strictly between the values at the ends of a monotone stretch is bracketed
//      there and refined by TOMS 748 (Boost.Math, to full double precision). Limitation: two
//      critical points closer than the sampling grid (~ chord / 2n) are missed; the kink then
//      lies inside a piece and shows in the quadrature's error estimate.
//   3. On each piece rho_c and kappa_c are linear in f, so rho_c(t) is a Chebyshev series;
//      tau is its exact antiderivative (no quadrature error in the optical depth), and the
//      emission int kappa rho exp(-tau) is first a 7- or 10-point Gauss-Legendre rule whose
//      a-priori error bound (the integrand is entire: Trefethen's Bernstein-ellipse bound, the
//      ellipse's maximum bounded through the series' coefficients, cell_integral.cpp
//      gauss_bounds) is within the tolerance below in every channel; that bound is then the
//      quadrature's error estimate. The 7 points are the Gauss-Kronrod rule's Gauss nodes, so
//      a miss costs no extra evaluation; the 10-point rule is used only where its bound is below
//      the rounding floor (it cannot miss). Measured: on the bench meshes (bench_cell_mesh.cpp)
//      every piece passes (72 % with 7 points, 28 % with 10); on tools/cell_accuracy's strongly
//      distorted cells with optical depths up to ~5 per cell 35 % pass, 65 % go on to
//      Gauss-Kronrod. The ellipses tried are rho = 4 .. 2048 (powers of 2), walked from 32 and
//      stopped once a bound is within the rounding floor, with a rigorous upper bound of exp
//      (gauss_bounds, exp_upper; before 2026-12-05 rho = 4 .. 32, all four, libm's exp: a tenth
//      of `rayint bench` box12's own time). The integrand at a rule's nodes is evaluated
//      vectorised over the nodes (cells/emission_nodes.hpp: Highway, the scalar operations in the
//      same order, fused multiply-adds where the target has them, exp Highway's Exp, documented
//      1 ulp, instead of libm's: results move at the rounding level and between SIMD targets). Otherwise 15-point Gauss-Kronrod (Boost.Math's nodes and weights),
//      globally adaptive: the subinterval with the largest |K - G| is halved (at most
//      256) until sum |K - G| <= kQuadratureTolerance = 1e-14 of the integral of |integrand|
//      (or 8 ulps of it, the rounding floor of the sums), or below the integrand's own rounding
//      noise: 64 eps (x1 - x0) (kappa_max (|v0| + |beta| (max|f_i| + |s0|)) + the same with rho
//      and kappa swapped). Where rho or kappa -> 0 at a breakpoint its relative error is
//      unbounded in double, so a channel's relative error there is bounded by that floor, not by
//      1e-14 (reports/cells/accuracy.md states both relative and absolute errors). All three
//      channels share the nodes (one evaluation of f and its antiderivative per node). Boost's own recursive
//      gauss_kronrod::integrate (1.74) is not used: its error estimate on [a, b] away from 0
//      did not shrink with the interval (2.6e-11 on [0.2, 0.2 + 1e-12], measured), which
//      drove it to its depth limit on short pieces.
// error_estimate adds, per channel, the quadrature's estimate and the propagated interpolation
// error (|beta_kappa| rho_max + kappa_max |beta_rho|) e_f * length + emission * |beta_rho| e_f *
// length (beta: the transfer functions' slopes on the piece), and the depth's |beta_rho| e_f *
// length; the largest channel's sum is reported.
// Failure (converged = false, `failure` says why; emission and depth are then not a result):
// a Newton solve that did not converge, a chord whose interpolant missed the tail target after
// the bisection budget, a quadrature that missed its tolerance by more than 10x.
//
// Accuracy against the independent 50-digit reference (reference/cell_reference.hpp), 600 random
// distorted cells per family (twisted and perturbed hexahedra, perturbed voxels, wedges in VTK's
// and gmsh's orientation, warped pyramids, 10-30 % of the edge; 4,803 chords,
// reports/cells/accuracy.md, made by tools/cell_accuracy.cpp): every chord converged; absolute
// error (emission + depth, values O(0.01-1)) <= 1.07e-14 in every family, median relative ~1e-15;
// no chord's error above its error_estimate. Relative errors reach 2.2e-11 only where a channel's
// value is itself tiny (absolute 8e-17 there). Tests [cells][isoparametric] re-check 30 chords.
// Cost (reports/cells/bench.md): on the bench's twisted 12^3 hexahedral mesh
// (bench/bench_cell_mesh.cpp, BM_mesh) the own render was 18-20x the split one before the
// Taylor-predicted samples, the chop and the monotonicity proof, 11.5-13x after; the Gauss
// rules with a-priori bounds, degree-8 starts and the face early-out: see bench.md (target 3x).
// On the affine box12 mesh (`rayint bench`, scripts/cells/bench_hex_meshes.py) own/split was
// 4.7-4.9x before the 2026-12-05 changes (vectorised integrand, the ellipse walk, no heap
// allocation per chord, the factorised cubic), ~3.0x after (reports/cells/bench_own29box_measurements.txt).
// On the twisted12 mesh 12.4-12.5x before hexahedra took f's own Taylor series (no samples) and
// the classification its Newton on the multilinear form, 6.7-7.5x after (2026-12-05,
// reports/cells/bench_own29twist_measurements.txt); 6.8-7.1x (own 6 % faster, the walk's star
// search filtered) on 2026-12-06 (reports/cells/bench_own29fast_measurements.txt).
#include <vector>

#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/quadratic_isoparametric.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

inline constexpr double kChebyshevTail = 64 * 2.220446049250313e-16;
inline constexpr int kMaxBisections = 6;
inline constexpr double kQuadratureTolerance = 1e-14;
inline constexpr double kChopFraction = 1.0 / 64;  // trailing coefficients dropped: <= eps max|f_i|
// f's own Taylor series (hexahedra, voxels: chord_scalar.hpp) is truncated where its tail is <= this
// fraction of the tail target, i.e. <= eps max|f_i| / 4: the truncation is systematic along the
// chord (not the samples' scattered rounding), so it is held below their noise. Measured with
// tools/cell_accuracy --seed 1, hex_twisted: at eps max|f_i| (1/64) the worst relative emission
// error rose 3.9e-14 -> 1.5e-13 (a near-zero channel, absolute 3.9e-16), at 1/256 it is main's;
// `rayint bench` twisted12 and gmsh-hex equally fast with both; at 1/1024 gmsh-hex 30 % slower.
inline constexpr double kSeriesTruncation = kChopFraction / 4;

enum class CellPath { linear_exact, polynomial, isoparametric };
const char* cell_path_name(CellPath path);  // "linear_exact", "polynomial", "isoparametric"

struct CellPieceIntegral {
  Rgb emission{};        // light leaving t_near toward the eye, nothing entering at t_far
  Rgb optical_depth{};   // int rho over the chord (world length)
  double error_estimate = 0.0;  // absolute, emission + depth of the worst channel
  CellPath path = CellPath::isoparametric;
  int pieces = 0;        // smooth pieces integrated (between crossings and critical points)
  int samples = 0;       // scalar evaluations (inverse-map solves on the isoparametric path)
  int max_degree = 0;    // largest Chebyshev degree used
  bool converged = true;
  const char* failure = "";  // why not converged ("" when converged)
};

// Front-to-back compositing: `near` then `far` behind it (C = C_near + exp(-D_near) C_far,
// D = D_near + D_far); the error estimates add, a failure of either is a failure.
CellPieceIntegral composite(const CellPieceIntegral& near, const CellPieceIntegral& far);

class LinearCellIntegrator {
 public:
  explicit LinearCellIntegrator(const TransferFunctions& tf);
  // The chord [t_near, t_far] (t_near <= t_far, both inside the cell, e.g. from chord()) of
  // ray.origin + t ray.direction; lengths are world lengths (|direction| need not be 1).
  // `start`, if given and finite: a parametric point near the chord's centre (ChordInterval::p_mid),
  // the first Newton solve's start instead of the cell's centre (the result is the same root).
  CellPieceIntegral integrate(const LinearCell& cell, const ViewRay& ray, double t_near,
                              double t_far, const Vec3* start = nullptr) const;
  // Forces the isoparametric (Newton) path on an affine cell too (for tests and measurements).
  CellPieceIntegral integrate_isoparametric(const LinearCell& cell, const ViewRay& ray,
                                            double t_near, double t_far) const;
  // A quadratic cell (cells/quadratic_isoparametric.hpp): the isoparametric path, or the
  // polynomial path for an affine one (a straight-edged tet10: f is a quadratic in t).
  CellPieceIntegral integrate(const QuadraticCell& cell, const ViewRay& ray, double t_near,
                              double t_far) const;
  const TransferFunctions& transfer() const { return *tf_; }

 private:
  CellPieceIntegral integrate_curved(const LinearCell& cell, const ViewRay& ray, double t_near,
                                     double t_far, bool use_newton, const Vec3* start = nullptr) const;
  // Steps 1-3 above for any scalar along the chord (F: double operator()(double t), members
  // `samples` and `ok`), n0 the first Chebyshev degree.
  template <class F>
  CellPieceIntegral integrate_sampled(F& sampler, double value_scale, const ViewRay& ray, double t_near,
                                      double t_far, int n0, CellPath path) const;
  const TransferFunctions* tf_;
  std::vector<double> breakpoints_;
  PieceSplitter splitter_;
};

}  // namespace rayint
