#pragma once
// Internals of the high-precision reference (reference.cpp), exposed for its tests and for
// calibration programs. Not part of the public interface: use reference.hpp.
#include <array>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "rayint/model/transfer_function.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint::reference_detail {

using Real = boost::multiprecision::cpp_bin_float_50;  // 168-bit significand, eps = 5.3e-51

// One channel of one piece in 50-digit arithmetic. s = distance from the exit (eye side);
// rho and kappa are linear in s, from *_exit at s = 0 to *_far at s = length.
struct PieceData {
  Real length;
  Real rho_far;
  Real rho_exit;
  Real kappa_far;
  Real kappa_exit;
};

// What integrate_piece computed and how (branch introspection for test failures and reports).
struct PieceQuadrature {
  Real transmittance;        // exp(-T), T = length * (rho_far + rho_exit) / 2
  Real transmittance_error;  // bound on |transmittance - exact|
  Real emission;             // Eq. 4 on the piece
  Real emission_error;       // bound on |emission - exact|: sum of the three below
  Real quadrature_error;     //   sum over subintervals of |Kronrod - Gauss|
  Real truncation_error;     //   bound on the part beyond tau_cut that was not integrated
  Real rounding_error;       //   bound on 50-digit rounding (exp series, recurrences, sums)
  Real optical_depth;        // T
  Real tau_cut;              // optical depth where integration stopped (T if not truncated)
  int rule = 0;              // Gauss-Kronrod points; 0 when no quadrature was needed
  int subintervals = 0;
  int refinements = 0;        // times the subintervals were doubled to meet the target
  int truncation_passes = 0;  // times tau_cut was raised to meet the target
  bool truncated = false;     // integration domain was cut at tau(s) = tau_cut < T
  bool converged = true;      // estimates met the target within their budgets
};

// The automatic method: rule, subintervals and truncation chosen from the optical depth, then
// refined within budgets until the estimates meet the internal target (see reference.cpp).
PieceQuadrature integrate_piece(const PieceData& piece);

// A forced method for calibration and for testing the error estimate on purpose-made coarse
// rules: `rule` in {15, 21, 31, 41, 51, 61}, `subintervals` >= 1, truncation at tau_cut
// (pass +infinity for none); no refinement.
PieceQuadrature integrate_piece_forced(const PieceData& piece, int rule, int subintervals,
                                       double tau_cut);

// exp(z) by a Taylor series on z / 2^k (|z / 2^k| <= 1/32) followed by k squarings, for the
// moderate arguments (|z| up to a few tens) at the quadrature nodes. `relative_error`, if
// given, receives a bound on |result / exp(z) - 1|.
Real exp_series(const Real& z, double* relative_error = nullptr);

// Transfer function evaluated in 50 digits at a double scalar, as the limit from below or from
// above: the stored value at a breakpoint (at a jump, its left or right value), the end value
// beyond the ends, else (v0 (s1 - s) + v1 (s - s0)) / (s1 - s0), whose two terms are
// non-negative, so the result has a few ulps relative error.
Real interpolate(const PiecewiseLinear& f, double s, bool from_above);

// A transfer function on the scalar interval containing f_mid: v0 + beta (f - s0), and its
// largest value on that interval (for tail bounds); the end value (beta 0) beyond the ends. The
// cell and polynomial references (cell_reference.cpp, poly_reference.cpp) integrate each piece
// of a chord with it.
struct LinearPart {
  Real v0, beta, s0, max_value;
};
LinearPart linear_part(const PiecewiseLinear& f, const Real& f_mid);

// A Gauss-Kronrod rule on [-1, 1] with Boost.Math's nodes and weights in 50 digits, as the
// quadrature above uses it (shared with reference/poly_reference.cpp): x[0] = 0 < x[1] < ... <
// x[size - 1], each x[j] > 0 standing for the pair -+x[j]; Kronrod weights; Gauss weights, 0 at
// the Kronrod-only nodes. `points` in {15, 21, 31, 41, 51, 61}; the tables live for the program.
struct GaussKronrodRule {
  int points = 0;
  std::size_t size = 0;
  const Real* x = nullptr;
  const Real* kronrod = nullptr;
  const Real* gauss = nullptr;
};
GaussKronrodRule gauss_kronrod_rule(int points);

// The rule on the panel [centre - w, centre + w] without the factor w: the Kronrod sum K and the
// embedded Gauss sum G of f at the nodes centre -+ w x[j]. The panel's integral is w K; w |K - G|
// is the estimate of its error both references use.
struct GaussKronrodSums {
  Real kronrod, gauss;
};
template <class F>
GaussKronrodSums gauss_kronrod_panel(const GaussKronrodRule& rule, const F& f, const Real& centre, const Real& w) {
  const Real f0 = f(centre);
  GaussKronrodSums s{rule.kronrod[0] * f0, rule.gauss[0] * f0};
  for (std::size_t j = 1; j < rule.size; ++j) {
    const Real pair = f(centre - w * rule.x[j]) + f(centre + w * rule.x[j]);
    s.kronrod += rule.kronrod[j] * pair;
    if (rule.gauss[j] != 0) s.gauss += rule.gauss[j] * pair;
  }
  return s;
}

// The unit roundoff of Real, 2^(1 - 168).
double unit_roundoff();
// The smallest double >= x (error bounds are rounded up).
double rounded_up(const Real& x);
// Throws std::invalid_argument unless every function has matching, non-empty point lists with
// non-decreasing finite scalars (a scalar at most twice: a jump) and finite values >= 0.
void check_transfer_functions(const TransferFunctions& tf);

// hi = x rounded to nearest double (ties to even), lo = (x - hi) rounded likewise.
ExtendedValue to_extended(const Real& x);
// |x - (v.hi + v.lo)|, exact in 50 digits for the values to_extended returns.
Real representation_error(const Real& x, const ExtendedValue& v);

// The running sums of a reference ray per channel, far -> near (reference_ray and
// reference_poly_ray): intensity, transmittance and the bound on the intensity's error.
struct RaySums {
  std::array<Real, kChannels> intensity, transmittance, error;
  // At the far end: the background, transmittance 1, no error. Throws
  // std::invalid_argument(`message`) unless the background is finite.
  RaySums(const Rgb& background, const char* message);
  // Composites piece `q` (transmittance T, emission E and their bounds dT, dE) onto channel c:
  // intensity = incoming * T + E, transmittance *= T, and the bound becomes
  //   error * (T + dT) + |incoming| dT + dE + data_error... + |intensity| 2 eps,
  // summed left to right; `data_error` are the terms for errors in the piece's own data (none
  // where the data are exact).
  template <class Quadrature, class... DataError>
  void add_piece(int c, const Quadrature& q, double eps, const DataError&... data_error) {
    const Real incoming = intensity[c];
    intensity[c] = incoming * q.transmittance + q.emission;
    transmittance[c] *= q.transmittance;
    error[c] = ((error[c] * (q.transmittance + q.transmittance_error) +
                 abs(incoming) * q.transmittance_error + q.emission_error) +
                ... + data_error) +
               abs(intensity[c]) * (2 * eps);
  }
  // Rounds into `out`: intensity and transmittance to_extended, error_bound the error plus the
  // representation error, rounded up.
  void round_into(ReferenceRay& out) const;
};

}  // namespace rayint::reference_detail
