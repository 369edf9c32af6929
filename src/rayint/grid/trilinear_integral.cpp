// The trilinear ray integral in double; method and thresholds in trilinear_integral.hpp.
//
// ACCURACY (tests/test_trilinear.cpp, [trilinear]) against reference_poly_ray in 50 digits on
// the same cubics, 208 rays (random rays, rays in grid planes, along grid edges, through grid
// vertices; a random 6x5x7 and a smooth 9x8x10 grid; non-grey transfer functions with 3-4
// breakpoints each, optical depths ~0.5 to ~100): worst relative error of the intensity 7.4e-16,
// of the transmittance 1.5e-14 (= eps * T for T ~ 100: the conditioning of exp(-T)).
#include "rayint/grid/trilinear_integral.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rayint/model/polynomial.hpp"

namespace rayint {

namespace {

using Cubic = std::array<double, 4>;
using Rule = boost::math::quadrature::gauss<double, 8>;

double horner(const Cubic& c, double x) { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }

// Bounds of a cubic on [0, h]: the hull of its Bernstein coefficients (contains the range).
void hull(const Cubic& c, double h, double& lo, double& hi) {
  const double a1 = c[1] * h, a2 = c[2] * h * h, a3 = c[3] * h * h * h;
  const double b[4] = {c[0], c[0] + a1 / 3.0, c[0] + (2.0 * a1 + a2) / 3.0, c[0] + a1 + a2 + a3};
  lo = std::min(std::min(b[0], b[1]), std::min(b[2], b[3]));
  hi = std::max(std::max(b[0], b[1]), std::max(b[2], b[3]));
}

// c(x0 + u) as a cubic in u (Taylor coefficients at x0).
Cubic shifted(const Cubic& c, double x0) {
  return {horner(c, x0), (3.0 * c[3] * x0 + 2.0 * c[2]) * x0 + c[1], 3.0 * c[3] * x0 + c[2], c[3]};
}

// The linear branch of f containing the scalar x: value = v0 + beta (x - x0).
struct Line {
  double v0 = 0.0, beta = 0.0, x0 = 0.0;
  double at(double x) const { return v0 + beta * (x - x0); }
};

Line line_at(const PiecewiseLinear& f, double x) {
  const auto& s = f.scalar;
  if (s.size() == 1 || x <= s.front()) return {f.value.front(), 0.0, 0.0};
  if (x >= s.back()) return {f.value.back(), 0.0, 0.0};
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), x) - s.begin());
  return {f.value[k - 1], (f.value[k] - f.value[k - 1]) / (s[k] - s[k - 1]), s[k - 1]};
}

// The line composed with the cubic g: a cubic in u.
Cubic compose(const Line& l, const Cubic& g) {
  return {l.v0 + l.beta * (g[0] - l.x0), l.beta * g[1], l.beta * g[2], l.beta * g[3]};
}

// tau(u) = int_0^u rho (rho a cubic).
double depth(const Cubic& rho, double u) {
  return u * (rho[0] + u * (rho[1] / 2.0 + u * (rho[2] / 3.0 + u * rho[3] / 4.0)));
}

}  // namespace

TrilinearIntegrator::TrilinearIntegrator(const TransferFunctions& tf)
    : tf_(&tf), breakpoints_(tf.breakpoints()), grey_(tf.grey()) {}

TrilinearRayResult TrilinearIntegrator::integrate(const VoxelGrid& grid, const ViewRay& ray,
                                                  const Rgb& background) const {
  thread_local std::vector<TrilinearCubic> cubics;
  thread_local std::vector<double> scratch;
  trilinear_cubics(grid, ray, cubics, scratch);
  TrilinearRayResult r;
  r.intensity = background;
  for (const TrilinearCubic& c : cubics) add_segment(c.coeffs, c.length, r, nullptr);
  return r;
}

Rgb TrilinearIntegrator::emission_only(const VoxelGrid& grid, const ViewRay& ray) const {
  thread_local std::vector<TrilinearCubic> cubics;
  thread_local std::vector<double> scratch;
  trilinear_cubics(grid, ray, cubics, scratch);
  TrilinearRayResult r;
  Rgb sum{0.0, 0.0, 0.0};
  for (const TrilinearCubic& c : cubics) add_segment(c.coeffs, c.length, r, &sum);
  return sum;
}

TrilinearRayResult TrilinearIntegrator::integrate(const PolyRay& ray) const {
  TrilinearRayResult r;
  r.intensity = ray.background;
  for (const PolySegment& seg : ray.segments) {
    if (!(std::isfinite(seg.length) && seg.length >= 0.0))
      throw std::invalid_argument("trilinear integral: segment length must be finite and >= 0");
    if (seg.coeffs.size() > 4) throw std::invalid_argument("trilinear integral: degree > 3");
    Cubic c{};
    for (std::size_t k = 0; k < seg.coeffs.size(); ++k) c[k] = seg.coeffs[k];
    add_segment(c, seg.length, r, nullptr);
  }
  return r;
}

void TrilinearIntegrator::add_segment(const Cubic& c, double length, TrilinearRayResult& r,
                                      Rgb* emission_only) const {
  ++r.cubes;
  if (!(length > 0.0)) return;
  double lo = 0.0, hi = 0.0;
  hull(c, length, lo, hi);
  const auto first_above = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), lo);
  if (first_above == breakpoints_.end() || !(*first_above < hi)) {
    add_piece(c, length, horner(c, 0.5 * length), r, emission_only);
    return;
  }
  ++r.split_cubes;
  const std::vector<double> knots =
      poly::split_points(std::vector<double>(c.begin(), c.end()), breakpoints_, length);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double h = knots[k + 1] - knots[k];
    if (!(h > 0.0)) continue;
    add_piece(shifted(c, knots[k]), h, horner(c, 0.5 * (knots[k] + knots[k + 1])), r, emission_only);
  }
}

void TrilinearIntegrator::add_piece(const Cubic& g, double h, double f_mid, TrilinearRayResult& r,
                                    Rgb* emission_only) const {
  ++r.pieces;
  double f_lo = 0.0, f_hi = 0.0;
  hull(g, h, f_lo, f_hi);
  const auto& x = Rule::abscissa();  // nodes in [0, 1] of the symmetric rule on [-1, 1]
  const auto& w = Rule::weights();
  // The quadrature nodes of the colour term and their weights w * rho(u) * exp(-(T - tau(u)))
  // (times the panel's half width): they depend on the density only, so a grey medium (one
  // density for all channels) computes them once for all three.
  thread_local std::vector<std::pair<double, double>> nodes;
  double T = 0.0, trans = 1.0;
  bool have_nodes = false, transparent = false;
  for (int c = 0; c < kChannels; ++c) {
    const std::size_t ch = static_cast<std::size_t>(c);
    const Line kappa_line = line_at(tf_->color[ch], f_mid);
    const bool reuse = grey_ && c > 0;
    Cubic rho{};
    if (!reuse) {
      const Line rho_line = line_at(tf_->density[ch], f_mid);
      rho = compose(rho_line, g);
      const double rho_max = std::max({rho_line.at(f_lo), rho_line.at(f_hi), 0.0});
      transparent = rho_max == 0.0;
      have_nodes = false;
      if (!transparent) {
        T = depth(rho, h);
        trans = std::exp(-T);
        nodes.clear();
        if (emission_only == nullptr) {
          // Start of the part that matters: depth to the exit below kTailDepth (tau monotone).
          double u0 = 0.0;
          if (T > kTailDepth) {
            double a = 0.0, b = h;
            for (int it = 0; it < 200 && b - a > 1e-16 * h; ++it) {
              const double m = 0.5 * (a + b);
              (T - depth(rho, m) > kTailDepth ? a : b) = m;
            }
            u0 = a;
          }
          const double span = h - u0;
          const double panels = std::max(1.0, std::ceil(span * rho_max / kPanelDepth));
          const long n = static_cast<long>(panels);
          const double p = span / panels, half = 0.5 * p;
          for (long j = 0; j < n; ++j) {
            const double mid = u0 + (static_cast<double>(j) + 0.5) * p;
            for (std::size_t i = 0; i < x.size(); ++i)
              for (int side = 0; side < (x[i] == 0.0 ? 1 : 2); ++side) {
                const double u = side == 0 ? mid + half * x[i] : mid - half * x[i];
                nodes.emplace_back(u, half * w[i] * horner(rho, u) * std::exp(-(T - depth(rho, u))));
              }
          }
        } else {  // int_0^h kappa rho du, degree 6: 8 nodes are exact
          for (std::size_t i = 0; i < x.size(); ++i)
            for (int side = 0; side < (x[i] == 0.0 ? 1 : 2); ++side) {
              const double u = 0.5 * h * (1.0 + (side == 0 ? x[i] : -x[i]));
              nodes.emplace_back(u, 0.5 * h * w[i] * horner(rho, u));
            }
        }
        have_nodes = true;
      }
    }
    if (transparent) continue;  // nothing absorbed or emitted here
    const Cubic kappa = compose(kappa_line, g);
    if (emission_only != nullptr) {
      double sum = 0.0;
      for (const auto& [u, wt] : nodes) sum += wt * horner(kappa, u);
      (*emission_only)[ch] += sum;
      continue;
    }
    const double kappa_exit = horner(kappa, h);
    double emission = kappa_exit * -std::expm1(-T);
    if (have_nodes && kappa_line.beta != 0.0 && (g[1] != 0.0 || g[2] != 0.0 || g[3] != 0.0)) {
      double q = 0.0;
      for (const auto& [u, wt] : nodes) q += wt * (horner(kappa, u) - kappa_exit);
      emission += q;
    }
    r.intensity[ch] = r.intensity[ch] * trans + emission;
    r.transmittance[ch] *= trans;
  }
}

}  // namespace rayint
