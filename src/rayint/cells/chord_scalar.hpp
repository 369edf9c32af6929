#pragma once
// The scalar of a linear cell along a ray, f(t) = sum_i N_i(p(t)) f_i with p(t) the inverse map
// of x = origin + t direction (cells/linear_cells.hpp), evaluated at the Chebyshev points of
// cells/cell_integral.hpp's isoparametric path: the cost of that path is these inverse maps.
//
// Multilinear form. Every linear cell's shape functions (VTK's tetra, voxel, hexahedron, wedge,
// pyramid) are multilinear in p = (r, s, t): their span lies in {1, r, s, t, rs, rt, st, rst}.
// So x(p) = sum_m X_m mono_m(p), the coefficients by Moebius inversion of x at the eight corners
// of the unit cube (for a hexahedron X_4 = x0 - x1 + x2 - x3, the rs term, ...; sums and
// differences of node coordinates, a few ulps each). One evaluation of x and J is then ~50
// flops, without the per-type shape-function tables. The form is derived once per cell by
// make_linear_cell (LinearCell::multilinear, linear_cells.hpp), and linear_cells.hpp's multilinear_newton is the Newton iteration on
// it (also the chord classification's, classify_chord_intervals). The scalar at a sampled point
// is taken from the nodal form (cell_scalar): f's monomial coefficients (of f_i - midrange) carry
// rounding ~ eps x the values' spread, and on 200 warped pyramids sampling f from them put one
// chord's error above its estimate; they serve the series below, with that rounding bounded.
//
// Taylor predictor. About the centre t_c of an interval [a, b] (half-length h), p(t_c + tau) =
// sum_k P_k tau^k: P_0 by Newton, and since x is multilinear the coefficient of tau^k of
// x(p(tau)) is J(P_0) P_k + Q_k(P_1 .. P_{k-1}) (Cauchy products of the r, s, t series, Taylor-
// mode differentiation), so J(P_0) P_k = direction [k = 1] - Q_k: one 3x3 inverse for all orders.
// Terms are added until |P_k| h^k <= kTaylorNegligible = 1e-17 twice in a row (far below the
// Newton step tolerance 4e-15) or k = kTaylorMaxOrder = 24. The series converges for |tau| below
// the distance to the nearest complex point where J is singular; on a nearly affine cell that is
// many chord lengths away and the prediction is exact to rounding.
//
// Acceptance is Newton's own (linear_cells.hpp inverse_map): a point is converged when the world
// residual |x(p) - x_target| is <= 8 eps * max(|x_target|, |x_i|), or after a Newton step of at
// most kNewtonStepTolerance; budget kNewtonMaxIterations, steps clamped to kNewtonMaxStep. The
// predicted point is only Newton's start, and from it at least one step is always taken (so a
// sample ends, as inverse_map's usually do, on a step of <= 4e-15: quadratic convergence leaves
// it exact to rounding; accepting a prediction on the residual alone put one warped pyramid's
// chord error above its estimate, tools/cell_accuracy). Where the series has not converged (a
// strongly distorted cell, a long chord) Newton runs on from it; if the prediction is not finite
// or lies more than 0.25 outside the domain, Newton starts from the previous converged point
// instead, then from the cell's centre (as cell_integral did before). Measured on the bench's
// twisted 12^3 mesh (bench/bench_cell_mesh.cpp): see reports/cells/bench.md.
//
// f's own series (hexahedra and voxels, since 2026-12-05). The same recursion gives f's Taylor
// coefficients a_k = h^k sum_m F_m (mono_m(p))_k (the monomials' series: r, s, t from P_k, rs,
// rt, st, rst by Cauchy products); where the series converged (above) and its tail beyond some
// degree m <= the order reached is <= eps max|f_i| / 4 (kSeriesTruncation of the interpolant's
// tail target, cell_integral.hpp), series_chebyshev converts a_0 .. a_m to Chebyshev coefficients and the chord needs no
// samples, no Newton solve per sample and no DCT. Its error bound (the interpolant's tail e_f,
// chord_scalar.cpp) adds to the truncation the rounding of F (<= 9 eps x the spread sum
// |f_i - midrange|, times the monomials' variation along the chord), of the orders' arithmetic
// ((16 + 8 cond(J) + 4 m) eps x sum_{k>=1} |a_k| over absolute values) and of a_0 = f(P_0) in the
// nodal form (16 eps max|f_i|); P_0 takes one polishing Newton step. Where the bound misses the
// interpolant's tail target, or the series did not converge, the samples follow from the same
// expansion. Measured (`rayint bench`, reports/cells/bench.md "Hexahedra's chord scalar from its
// own Taylor series"): every chord of the twisted grid takes it (mean degree 8.4), 97 % of gmsh-hex's (7.3);
// own time 1.7x lower on the twisted grid; eval's max errors against the 50-digit reference unchanged;
// wedges and pyramids keep the samples (taylor_tail's reason).
#include <array>

#include "rayint/cells/linear_cells.hpp"

namespace rayint {

inline constexpr int kTaylorMaxOrder = 24;
inline constexpr double kTaylorNegligible = 1e-17;

// An affine cell's scalar along the ray on [a, b] (cell.affine: voxel, hexahedron or wedge):
// p(t) = A^-1 (o + t d - x0) is linear, so with t = (a + b) / 2 + x (b - a) / 2 every shape
// function N_i(p(x)) is a product of at most three linear factors in x and f = sum_i N_i f_i a
// polynomial of degree <= 3: c[0..3] its Chebyshev coefficients on x in [-1, 1], multiplied out
// (no samples): a wedge in the nodal form, a hexahedron or voxel factorised along r, s, t (the
// same trilinear form, 7 products instead of 16). Returns the coefficients' rounding scale: 8
// eps x the same expression over the terms' absolute values (products of <= 3 factors, sums of
// <= 8 terms; for the factorised form the absolute values go through every stage).
double affine_chord_chebyshev(const LinearCell& cell, const ViewRay& ray, double a, double b, std::array<double, 4>& c);

class ChordScalar {
 public:
  // `start`: Newton's first start (a point near the chord, e.g. ChordInterval::p_mid) when given,
  // finite and within 0.25 of the domain; else the cell's centre.
  ChordScalar(const LinearCell& cell, const ViewRay& ray, const Vec3* start = nullptr);
  // Sets the Taylor predictor about the centre of [a, b] (a Newton solve there, ending on at
  // least one step) and f's series. Returns false when that solve did not converge (sampling
  // still works, from warm starts only). A second call on the same [a, b] reuses the expansion.
  bool expand(double a, double b);
  // f(t); false when the inverse map did not converge (from every start).
  bool sample(double t, double& f);
  // A bound of sum_{k > n} |a_k|, a_k the Taylor coefficients of f about the centre of the last
  // expand()'s [a, b] in x = (t - t_c) / h: f(t) = sum_k a_k x^k. It bounds the Chebyshev
  // coefficients above degree n (x^k = sum_j b_kj T_j with sum_j |b_kj| = 1), so degree-n
  // interpolation is off by at most twice it (plus the series' own truncation, whose terms were
  // below kTaylorNegligible). Infinite when the series was not expanded to convergence, and
  // for wedges and pyramids (see chord_scalar.cpp).
  double taylor_tail(int n) const;
  // f on the last expand()'s [a, b] from its Taylor series alone (no samples, no DCT), as
  // Chebyshev coefficients c[0 .. degree] in x = (t - t_c) / h: the series truncated at the
  // smallest degree m whose taylor_tail(m) is <= `chop`, converted exactly (a table of x^k's
  // Chebyshev coefficients). `error` bounds |f - sum c_k T_k| on the chord: taylor_tail(m) plus
  // the rounding of f's monomial coefficients, of the series' arithmetic (scaled by J's
  // condition number) and of the nodal f at the centre (see chord_scalar.cpp). False where
  // taylor_tail is infinite (not converged; wedges, pyramids) or no degree <= the series' order
  // meets `chop`.
  bool series_chebyshev(double chop, std::array<double, kTaylorMaxOrder + 1>& c, int& degree, double& error) const;

  int samples = 0;           // sample() calls
  int newton_steps = 0;      // Newton steps taken (0 when every prediction was accepted)
  int predicted = 0;         // samples converged by the one Newton step from their predicted point

 private:
  bool newton(const Vec3& target, Vec3& p, bool step_first);
  const MultilinearForm* m_;  // cell_->multilinear
  const LinearCell* cell_;
  Vec3 o_, d_;
  Vec3 start_;  // last converged point
  double t_c_ = 0.0;
  double a_ = 0.0, b_ = 0.0;  // the last expand()'s interval, and its result
  bool expanded_ = false;
  double f_c_ = 0.0;       // f at P_0 from the nodal form (the series' a_0)
  double condition_ = 0.0; // |J(P_0)| |J(P_0)^-1| (infinity norms)
  int order_ = -1;  // -1: no expansion
  bool converged_ = false;  // the series' last two terms were negligible
  // Entries 0 .. order_ are set by expand() and only those are read (not initialised: the
  // integrator constructs one ChordScalar per chord, and zeroing these 1.2 kB was ~1 % of `rayint
  // bench` twisted12).
  std::array<Vec3, kTaylorMaxOrder + 1> P_;
  std::array<double, kTaylorMaxOrder + 1> f_series_;  // a_k = f_k h^k
  std::array<double, kTaylorMaxOrder + 1> f_abs_;     // the same sums over absolute values
  std::array<double, kTaylorMaxOrder + 1> mono_abs_;  // h^k sum of |coefficients| of r, s, t, rs, rt, st, rst
};

}  // namespace rayint
