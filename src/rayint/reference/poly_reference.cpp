// The 50-digit reference for a scalar that is a polynomial along the ray.
//
// What it computes. On a segment of length L the scalar is f(s) = sum_k c_k s^k, s the distance
// from the far end (model/poly_ray.hpp). The transfer functions rho(f), kappa(f) (Williams &
// Max 1992, Sec. 3.1) are piecewise linear in f, so along the ray they are piecewise
// polynomial in s with kinks where f crosses a breakpoint. Light enters at s = 0 and reaches
// the eye at s = L:  I <- I exp(-T_k) + emission_k  over pieces k, with, on a piece of length
// L_k and u the distance from its exit (eye side),
//   tau(u) = integral_0^u rho,   T_k = tau(L_k),
//   emission_k = integral_0^{L_k} kappa(u) rho(u) exp(-tau(u)) du         (Eq. 4).
//
// Independence: nothing here calls the closed form (integrators/exact.*), the linear reference
// (reference.cpp's piece quadrature) or the double-precision splitting (model/pieces.*,
// cells/). It shares with them only Boost's Gauss-Kronrod nodes (reference_detail::
// gauss_kronrod_rule, the tables reference.cpp uses) and the root-finding algorithm of
// model/polynomial.hpp, instantiated here in cpp_bin_float_50 (the cells' ODE path runs it in
// double); that algorithm is tested on its own against polynomials with known roots.
//
// Methods:
//   - Pieces: poly::split_points in 50 digits, at the critical points of f and at every
//     crossing of a breakpoint of any of the six functions (TOMS 748 to 167 bits). On a piece f
//     is monotone and between two consecutive breakpoints, so rho = v0 + beta (f - s0) is a
//     polynomial in u, re-expanded at the piece's exit (poly::shifted), and tau is its exact
//     antiderivative: no quadrature error in T.
//   - emission_k: composite 61-point Gauss-Kronrod on n equal subintervals, n from the optical
//     depth (<= 18 per subinterval, the 61-point limit calibrated in reference.cpp for linear
//     rho), doubled until sum h |K - G| <= 1e-36 of the emission (budget 8 doublings; then
//     std::runtime_error). exp(-tau) by Boost.Multiprecision's exp at every node.
//   - Thick pieces (T_k > 140): integration stops where tau = tau_cut (TOMS 748 on the monotone
//     tau); the rest is at most max kappa * exp(-tau_cut), added to the error and raised past
//     1e-36 of the emission by increasing tau_cut (as reference.cpp does).
// Error bound per channel: quadrature estimate + truncation + rounding (node values
// (8 degree + 4 tau_cut + 70) ulps, compositing 2 ulps per piece) + |x - (hi + lo)|.
// Accuracy (tests/test_cells.cpp [cells]): against hand-derived integrals (quadratic and quartic
// scalars with constant kappa, crossing breakpoints; constant rho with kappa quadratic in s)
// and against reference_ray on linear scalars: within 1e-30 relative, the bound never below
// the true error.
#include "rayint/reference/poly_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "rayint/model/polynomial.hpp"
#include "rayint/reference/reference_detail.hpp"

namespace rayint {
namespace {

using reference_detail::LinearPart;
using reference_detail::linear_part;
using reference_detail::Real;
using Poly = std::vector<Real>;

constexpr double kTargetRelative = 1e-36;  // as reference.cpp: six digits below the claim
constexpr double kTauCut = 140.0;          // exp(-140) = 1.6e-61
constexpr double kMaxIncrement = 18.0;     // optical depth per 61-point subinterval
constexpr int kRule = 61;
constexpr int kMaxDoublings = 8;
constexpr int kMaxTruncationPasses = 4;

// v0 + beta (g(u) - s0) as a polynomial in u.
Poly compose(const LinearPart& part, const Poly& g) {
  Poly p(g.size(), Real(0));
  for (std::size_t k = 0; k < g.size(); ++k) p[k] = part.beta * g[k];
  p[0] = part.v0 + part.beta * (g[0] - part.s0);
  return p;
}

struct PieceResult {
  Real transmittance, transmittance_error;
  Real emission, emission_error;
  Real tau_cut;  // depth where integration stopped (T if not truncated)
  int subintervals = 0;
};

struct Sums {
  Real kronrod, estimate;
};

Sums gauss_kronrod(const Poly& rho, const Poly& kappa, const Poly& tau, const Real& u_end,
                   int n_sub) {
  const reference_detail::GaussKronrodRule rule = reference_detail::gauss_kronrod_rule(kRule);
  const Real h = u_end / (2 * n_sub);
  Sums out;
  auto integrand = [&](const Real& u) {
    return poly::eval(kappa, u) * poly::eval(rho, u) * exp(-poly::eval(tau, u));
  };
  for (int m = 0; m < n_sub; ++m) {
    const Real c = h * (2 * m + 1);
    const reference_detail::GaussKronrodSums panel = reference_detail::gauss_kronrod_panel(rule, integrand, c, h);
    out.kronrod += h * panel.kronrod;
    out.estimate += h * abs(panel.kronrod - panel.gauss);
  }
  return out;
}

PieceResult integrate_piece(const Poly& rho, const Poly& kappa, const Real& length,
                            const Real& kappa_max, int degree) {
  const double eps = reference_detail::unit_roundoff();
  PieceResult r;
  const Poly tau = poly::antiderivative(rho);
  const Real T = poly::eval(tau, length);
  r.transmittance = exp(-T);
  r.transmittance_error = r.transmittance * ((4 * T + 8 + 4 * degree) * eps);
  r.tau_cut = T;
  if (length == 0 || T <= 0 || kappa_max == 0) return r;

  Real tau_cut = kTauCut;
  Sums sums;
  for (int pass = 0;; ++pass) {
    Real u_end = length;
    const bool truncated = T > tau_cut;
    if (truncated) {
      Poly shifted_tau = tau;
      shifted_tau[0] -= tau_cut;
      u_end = poly::detail::bracketed_root(shifted_tau, Real(0), length, Real(-tau_cut), T - tau_cut);
    }
    r.tau_cut = truncated ? tau_cut : T;
    int n_sub = std::max(1, static_cast<int>(std::ceil(static_cast<double>(r.tau_cut) / kMaxIncrement)));
    for (int d = 0;; ++d) {
      sums = gauss_kronrod(rho, kappa, tau, u_end, n_sub);
      if (sums.estimate <= kTargetRelative * abs(sums.kronrod)) break;
      if (d == kMaxDoublings)
        throw std::runtime_error("reference_poly_ray: quadrature missed 1e-36 after 8 doublings");
      n_sub *= 2;
    }
    r.subintervals = n_sub;
    Real tail = truncated ? kappa_max * exp(-tau_cut) : Real(0);
    if (truncated && tail > kTargetRelative * sums.kronrod && pass < kMaxTruncationPasses) {
      tau_cut += log(tail / (kTargetRelative * sums.kronrod)) + 1;
      continue;
    }
    r.emission = sums.kronrod;
    r.emission_error = sums.estimate + tail +
                       abs(sums.kronrod) * ((8.0 * degree + 4 * r.tau_cut + 70) * eps);
    return r;
  }
}

}  // namespace

ReferenceRay reference_poly_ray(const TransferFunctions& tf, const PolyRay& ray) {
  reference_detail::check_transfer_functions(tf);
  const double eps = reference_detail::unit_roundoff();
  std::vector<Real> levels;
  for (double b : tf.breakpoints()) levels.emplace_back(b);

  ReferenceRay out;
  reference_detail::RaySums sums(ray.background, "reference_poly_ray: background must be finite");
  for (const PolySegment& seg : ray.segments) {
    if (!(std::isfinite(seg.length) && seg.length >= 0))
      throw std::invalid_argument("reference_poly_ray: segment length must be finite and >= 0");
    Poly f;
    for (double c : seg.coeffs) {
      if (!std::isfinite(c))
        throw std::invalid_argument("reference_poly_ray: coefficients must be finite");
      f.emplace_back(c);
    }
    if (f.empty()) f.emplace_back(0);
    if (seg.length == 0) continue;
    const Real L = seg.length;
    const int degree = std::max(0, poly::degree(f));
    const std::vector<Real> knots = poly::split_points(f, levels, L);
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      const Real& s_far = knots[k];
      const Real& s_exit = knots[k + 1];
      const Real piece_length = s_exit - s_far;
      const Real f_mid = poly::eval(f, (s_far + s_exit) / 2);
      const Poly g = poly::shifted(f, s_exit, -1);  // f at distance u before the exit
      for (int c = 0; c < kChannels; ++c) {
        const LinearPart rho_part = linear_part(tf.density[c], f_mid);
        const LinearPart kappa_part = linear_part(tf.color[c], f_mid);
        const PieceResult q = integrate_piece(compose(rho_part, g), compose(kappa_part, g),
                                              piece_length, kappa_part.max_value, degree);
        sums.add_piece(c, q, eps);  // exact piece data: no data error terms
        out.subintervals += q.subintervals;
      }
      ++out.pieces;
    }
  }
  sums.round_into(out);
  return out;
}

}  // namespace rayint
