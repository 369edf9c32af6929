// The trilinear ray integral in double; method and thresholds in trilinear_integral.hpp.
//
// ACCURACY (tests/test_trilinear.cpp, [trilinear]) against reference_poly_ray in 50 digits on
// the same cubics, 208 rays (random rays, rays in grid planes, along grid edges, through grid
// vertices; a random 6x5x7 and a smooth 9x8x10 grid; non-grey transfer functions with 3-4
// breakpoints each, optical depths ~0.5 to ~100): worst relative error of the intensity 7.4e-16,
// of the transmittance 1.5e-14 (= eps * T for T ~ 100: the conditioning of exp(-T)).
#include "rayint/grid/trilinear_integral.hpp"

#include <algorithm>
#include <map>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
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

// The linear branch of f containing the scalar x: value = v0 + beta (x - x0); for gradients the
// node it came from: the interval's lower node `node` (interval = true, span its width) or the
// end node whose value is extended (interval = false).
struct Line {
  double v0 = 0.0, beta = 0.0, x0 = 0.0;
  std::size_t node = 0;
  bool interval = false;
  double span = 0.0;
  double at(double x) const { return v0 + beta * (x - x0); }
};

Line line_at(const PiecewiseLinear& f, double x) {
  const auto& s = f.scalar;
  if (s.size() == 1 || x <= s.front()) return {f.value.front(), 0.0, 0.0, 0, false, 0.0};
  if (x >= s.back()) return {f.value.back(), 0.0, 0.0, s.size() - 1, false, 0.0};
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), x) - s.begin());
  const double span = s[k] - s[k - 1];
  return {f.value[k - 1], (f.value[k] - f.value[k - 1]) / span, s[k - 1], k - 1, true, span};
}

// The line composed with the cubic g: a cubic in u.
Cubic compose(const Line& l, const Cubic& g) {
  return {l.v0 + l.beta * (g[0] - l.x0), l.beta * g[1], l.beta * g[2], l.beta * g[3]};
}

// tau(u) = int_0^u rho (rho a cubic).
double depth(const Cubic& rho, double u) {
  return u * (rho[0] + u * (rho[1] / 2.0 + u * (rho[2] / 3.0 + u * rho[3] / 4.0)));
}

// The points and weights of the colour term's composite Gauss-Legendre rule on a piece of length
// h with density cubic rho, depth T and density bound rho_max > 0: panels of depth <= kPanelDepth
// from where the depth to the exit falls below kTailDepth (tau is monotone). Each entry is
// (u, half panel width * GL weight); the integrand's factor rho(u) exp(-(T - tau(u))) is the
// caller's.
void quadrature_points(const Cubic& rho, double h, double T, double rho_max,
                       std::vector<std::pair<double, double>>& out) {
  const auto& x = Rule::abscissa();  // nodes in [0, 1] of the symmetric rule on [-1, 1]
  const auto& w = Rule::weights();
  out.clear();
  double u0 = 0.0;
  if (T > TrilinearIntegrator::kTailDepth) {
    double a = 0.0, b = h;
    for (int it = 0; it < 200 && b - a > 1e-16 * h; ++it) {
      const double m = 0.5 * (a + b);
      (T - depth(rho, m) > TrilinearIntegrator::kTailDepth ? a : b) = m;
    }
    u0 = a;
  }
  const double span = h - u0;
  const double panels = std::max(1.0, std::ceil(span * rho_max / TrilinearIntegrator::kPanelDepth));
  const long n = static_cast<long>(panels);
  const double p = span / panels, half = 0.5 * p;
  for (long j = 0; j < n; ++j) {
    const double mid = u0 + (static_cast<double>(j) + 0.5) * p;
    for (std::size_t i = 0; i < x.size(); ++i)
      for (int side = 0; side < (x[i] == 0.0 ? 1 : 2); ++side)
        out.emplace_back(side == 0 ? mid + half * x[i] : mid - half * x[i], half * w[i]);
  }
}

// The pieces of one cube (cubic c on [0, length]) between the transfer functions' breakpoints:
// f(g, h, f_mid, knot) per piece, g the cubic shifted to the piece's far end `knot`, f_mid the
// scalar at its middle (which picks the functions' linear branch). A cube whose Bernstein hull
// holds no breakpoint strictly inside is one piece; otherwise poly::split_points cuts it (and
// `split` counts it).
template <class F>
void visit_pieces(const Cubic& c, double length, const std::vector<double>& breakpoints, F&& f, long& split) {
  if (!(length > 0.0)) return;
  double lo = 0.0, hi = 0.0;
  hull(c, length, lo, hi);
  const auto first_above = std::upper_bound(breakpoints.begin(), breakpoints.end(), lo);
  if (first_above == breakpoints.end() || !(*first_above < hi)) {
    f(c, length, horner(c, 0.5 * length), 0.0);
    return;
  }
  ++split;
  const std::vector<double> knots =
      poly::split_points(std::vector<double>(c.begin(), c.end()), breakpoints, length);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double h = knots[k + 1] - knots[k];
    if (!(h > 0.0)) continue;
    f(shifted(c, knots[k]), h, horner(c, 0.5 * (knots[k] + knots[k + 1])), knots[k]);
  }
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
  visit_pieces(c, length, breakpoints_, [&](const Cubic& g, double h, double f_mid, double) {
    add_piece(g, h, f_mid, r, emission_only);
  }, r.split_cubes);
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
          quadrature_points(rho, h, T, rho_max, nodes);
          for (auto& [u, wt] : nodes) wt = wt * horner(rho, u) * std::exp(-(T - depth(rho, u)));
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

// ---------------------------------------------------------------------------------------------
// Gradient. The derivative of the integral above, piece by piece, with the same pieces (the
// cube walk, visit_pieces' cuts, the branch picked at f_mid) and the same quadrature points
// (quadrature_points): per piece and channel, with rho(u) = sum_m rho_m u^m and kappa(u) =
// sum_m kappa_m u^m (the composed cubics), tau and T as above, E_j = exp(-(T - tau(u_j))) and
// wt_j = cw_j rho(u_j) E_j at the points u_j with weights cw_j, the light leaving is
//     I_out = I_in e^{-T} + kappa(h) (1 - e^{-T}) + sum_j wt_j (kappa(u_j) - kappa(h)),
// and its derivatives are
//     d/dT       = e^{-T} (kappa(h) - I_in) - sum_j wt_j (kappa(u_j) - kappa(h)),
//     d/d rho_m  = d/dT h^{m+1}/(m+1) + sum_j (kappa(u_j) - kappa(h)) cw_j E_j (u_j^m + rho(u_j) u_j^{m+1}/(m+1)),
//     d/d kappa_m = h^m (1 - e^{-T}) + sum_j wt_j (u_j^m - h^m),
// the derivative of the rule, i.e. the same rule applied to the derivative's integrand (smooth on
// the piece: 8-point Gauss-Legendre on panels of depth <= kPanelDepth integrates it as accurately
// as the forward one). The forward skips a transparent piece (rho = 0 on it) and the colour
// term where kappa or f is constant on the piece; those terms are 0 there but their derivatives
// are not (a density node value raised inside a transparent stretch absorbs), so the gradient
// evaluates every term on every piece. Then rho_m = beta_rho g_m (+ v0 - beta x0 for m = 0) with
// g the piece's scalar cubic and (v0, beta, x0) the density's branch at f_mid (likewise kappa):
//   - d/d g_m = beta_rho d/d rho_m + beta_kappa d/d kappa_m, and g = sum over the cube's corners
//     of value_c * (corner cubic c shifted to the piece, trilinear_corner_cubics), so
//     d/d value_c = sum_m d/d g_m * (corner cubic c)_m;
//   - d/d v0 = d/d rho_0, d/d beta = d/d rho_0 (g_0 - x0) + sum_{m>=1} d/d rho_m g_m,
//     d/d x0 = -beta d/d rho_0, to the branch's two nodes (beta = (v_k - v_{k-1})/(p_k - p_{k-1}))
//     or, on a constant extension, to the end node's value.
// The cut points move with the values and nodes, but rho(f) and kappa(f) are continuous there,
// so those terms cancel (Leibniz): the pieces are held fixed. The tail skipped where the depth to
// the exit exceeds kTailDepth is skipped in the derivative too (its share < e^{-50}).
// Reverse accumulation: each piece's derivatives are scaled by the transmittance of everything
// nearer than it (the adjoint), computed after the forward sweep.
// Accuracy: tests/test_trilinear_grad.cpp ([trilinear_grad]) against fourth-order differences
// (h = 1e-5) of the 50-digit polynomial reference on the trilinear tests' hard rays, 56 rays:
// voxel values worst 2.1e-11, node values and positions 5.2e-11 of the channel's largest entry.

double TrilinearGradient::channel_scale(int c) const {
  double m = 0.0;
  const bool skip_nan = !undefined.empty();
  const auto take = [&m, skip_nan](double v) {
    if (std::isnan(v) && skip_nan) return;
    m = std::isnan(v) || std::isnan(m) ? std::nan("") : std::max(m, std::fabs(v));
  };
  for (const Rgb& d : d_value) take(d[c]);
  for (const auto* block : {&density, &color})
    for (const NodeDerivative& n : (*block)[static_cast<std::size_t>(c)]) {
      take(n.value);
      take(n.position);
    }
  return m;
}

TrilinearGradient TrilinearIntegrator::gradient(const VoxelGrid& grid, const ViewRay& ray,
                                                const Rgb& background) const {
  const bool jumps = tf_->has_jump();
  TrilinearGradient out;
  for (int c = 0; c < kChannels; ++c) {
    const std::size_t ch = static_cast<std::size_t>(c);
    out.density[ch].assign(tf_->density[ch].scalar.size(), NodeDerivative{});
    out.color[ch].assign(tf_->color[ch].scalar.size(), NodeDerivative{});
  }
  out.intensity = integrate(grid, ray, background).intensity;
  std::vector<TrilinearCubic> cubics;
  std::vector<double> scratch;
  trilinear_cubics(grid, ray, cubics, scratch);

  // Forward: per piece and channel the local derivatives of I_out (before the adjoint).
  struct Local {
    double trans = 1.0;
    double dg[4] = {0.0, 0.0, 0.0, 0.0};
    Line rho_line, kappa_line;
    double rho_v0 = 0.0, rho_beta = 0.0, rho_x0 = 0.0, kappa_v0 = 0.0, kappa_beta = 0.0, kappa_x0 = 0.0;
  };
  struct PieceRecord {
    std::size_t cube = 0;
    double knot = 0.0;
    double f_mid = 0.0, f_far = 0.0, f_exit = 0.0;  // scalar at its middle and ends
    double slope_far = 0.0;                          // dG/du at its far end (G: the cube's cubic)
    Rgb light_in{};                                  // light entering it
    Local ch[kChannels];
  };
  std::vector<PieceRecord> pieces;
  std::vector<std::pair<double, double>> points;
  Rgb light = background;
  long split = 0;
  for (std::size_t m = 0; m < cubics.size(); ++m) {
    visit_pieces(cubics[m].coeffs, cubics[m].length, breakpoints_, [&](const Cubic& g, double h, double f_mid, double knot) {
      PieceRecord rec;
      rec.cube = m;
      rec.knot = knot;
      rec.f_mid = f_mid;
      rec.f_far = g[0];
      rec.f_exit = horner(g, h);
      rec.slope_far = g[1];
      rec.light_in = light;
      double f_lo = 0.0, f_hi = 0.0;
      hull(g, h, f_lo, f_hi);
      for (int c = 0; c < kChannels; ++c) {
        const std::size_t ch = static_cast<std::size_t>(c);
        Local& L = rec.ch[ch];
        L.rho_line = line_at(tf_->density[ch], f_mid);
        L.kappa_line = line_at(tf_->color[ch], f_mid);
        const Cubic rho = compose(L.rho_line, g), kappa = compose(L.kappa_line, g);
        const double rho_max = std::max({L.rho_line.at(f_lo), L.rho_line.at(f_hi), 0.0});
        const bool transparent = rho_max == 0.0;
        const double T = transparent ? 0.0 : depth(rho, h);
        const double trans = transparent ? 1.0 : std::exp(-T);
        const double absorbed = transparent ? 0.0 : -std::expm1(-T);
        quadrature_points(rho, h, T, rho_max, points);
        const double kappa_exit = horner(kappa, h);
        double q = 0.0;
        double d_rho[4] = {0.0, 0.0, 0.0, 0.0}, d_kappa[4] = {0.0, 0.0, 0.0, 0.0};
        double h_pow[5] = {1.0, h, h * h, h * h * h, h * h * h * h};
        for (const auto& [u, cw] : points) {
          const double rho_u = horner(rho, u);
          const double e = std::exp(-(T - depth(rho, u)));
          const double wt = cw * rho_u * e;
          const double dk = horner(kappa, u) - kappa_exit;
          q += wt * dk;
          double u_pow = 1.0;
          for (int k = 0; k < 4; ++k) {
            d_rho[k] += dk * cw * e * (u_pow + rho_u * u_pow * u / (k + 1));
            d_kappa[k] += wt * (u_pow - h_pow[k]);
            u_pow *= u;
          }
        }
        const double d_T = trans * (kappa_exit - light[ch]) - q;
        for (int k = 0; k < 4; ++k) {
          d_rho[k] += d_T * h_pow[k + 1] / (k + 1);
          d_kappa[k] += h_pow[k] * absorbed;
          L.dg[k] = L.rho_line.beta * d_rho[k] + L.kappa_line.beta * d_kappa[k];
        }
        L.rho_v0 = d_rho[0];
        L.rho_x0 = -L.rho_line.beta * d_rho[0];
        L.rho_beta = d_rho[0] * (g[0] - L.rho_line.x0) + d_rho[1] * g[1] + d_rho[2] * g[2] + d_rho[3] * g[3];
        L.kappa_v0 = d_kappa[0];
        L.kappa_x0 = -L.kappa_line.beta * d_kappa[0];
        L.kappa_beta =
            d_kappa[0] * (g[0] - L.kappa_line.x0) + d_kappa[1] * g[1] + d_kappa[2] * g[2] + d_kappa[3] * g[3];
        L.trans = trans;
        // The forward's light, as add_piece composites it (colour term where it computes it).
        if (!transparent) {
          double emission = kappa_exit * absorbed;
          if (L.kappa_line.beta != 0.0 && (g[1] != 0.0 || g[2] != 0.0 || g[3] != 0.0)) emission += q;
          light[ch] = light[ch] * trans + emission;
        }
      }
      pieces.push_back(rec);
    }, split);
  }

  // Reverse: adjoint = transmittance of everything nearer than the piece.
  std::map<std::size_t, Rgb> voxel;
  const auto to_nodes = [](const Line& line, double bar_v0, double bar_beta, double bar_x0,
                           std::vector<NodeDerivative>& nodes) {
    if (!line.interval) {
      nodes[line.node].value += bar_v0;
      return;
    }
    const double per_value = bar_beta / line.span, per_position = bar_beta * line.beta / line.span;
    nodes[line.node].value += bar_v0 - per_value;
    nodes[line.node + 1].value += per_value;
    nodes[line.node].position += bar_x0 + per_position;
    nodes[line.node + 1].position -= per_position;
  };
  // A jump crossed inside a cube, between pieces `before` and `after` (adjacent, same cube), at
  // u* with G(u*) = x_j: as for segments (integrators/ray_gradient_chain.hpp, add_jump_crossing),
  // dI/du* = A [rho_b (kappa_b - I*) - rho_a (kappa_a - I*)] with the one-sided values from each
  // piece's branch at x_j, I* the light at u*, A the transmittance from u* to the eye. u* moves
  // with x_j (du*/dx_j = 1/G'(u*)) and with a corner value v (G = sum v B_v: du*/dv =
  // -B_v(u*)/G'(u*)). The cut points of continuous breakpoints move too, but there the two sides
  // agree and the term is 0 (Leibniz, above). Where G touches x_j (a cut at a critical point, or
  // G'(u*) = 0, or a cube face or ray end exactly at x_j) the derivatives in x_j and in that
  // cube's corner values do not exist: NaN, with the reason.
  static const char* const kChannelName[kChannels] = {"r", "g", "b"};
  const auto mark = [&out](const std::string& why) {
    if (!out.undefined.empty()) out.undefined += "; ";
    out.undefined += why;
  };
  // The first node of a jump of f strictly between a and b (either order), or kNoJump.
  const auto jump_between = [](const PiecewiseLinear& f, double a, double b) {
    const double lo = std::min(a, b), hi = std::max(a, b);
    for (std::size_t i = 0; i + 1 < f.scalar.size(); ++i)
      if (f.scalar[i] == f.scalar[i + 1] && lo < f.scalar[i] && f.scalar[i] < hi) return i;
    return kNoJump;
  };
  std::vector<std::pair<std::size_t, int>> nan_cubes;  // (cube, channel) whose corners have no derivative
  const auto touch = [&](std::size_t cube, int c, double x, const char* where) {
    for (const bool is_density : {true, false}) {
      const PiecewiseLinear& f = is_density ? tf_->density[static_cast<std::size_t>(c)] : tf_->color[static_cast<std::size_t>(c)];
      const std::size_t i = jump_node(f, x);
      if (i == kNoJump) continue;
      (is_density ? out.density : out.color)[static_cast<std::size_t>(c)][i].position = std::nan("");
      nan_cubes.emplace_back(cube, c);
      mark(std::string("the ray touches the jump of ") + (is_density ? "density " : "color ") + kChannelName[c] +
           " at " + where);
    }
  };
  Rgb adjoint{1.0, 1.0, 1.0};
  std::size_t corners_of = cubics.size();
  std::array<std::array<double, 4>, 8> corners{};
  for (std::size_t k = pieces.size(); k-- > 0;) {
    const PieceRecord& rec = pieces[k];
    if (rec.cube != corners_of) {
      corners = trilinear_corner_cubics(grid, ray, cubics[rec.cube]);
      corners_of = rec.cube;
    }
    for (int corner = 0; corner < 8; ++corner) {
      const Cubic b = shifted(corners[static_cast<std::size_t>(corner)], rec.knot);
      Rgb d{};
      for (int c = 0; c < kChannels; ++c) {
        const Local& L = rec.ch[c];
        d[c] = adjoint[c] * (L.dg[0] * b[0] + L.dg[1] * b[1] + L.dg[2] * b[2] + L.dg[3] * b[3]);
      }
      Rgb& acc = voxel[trilinear_corner_index(grid, cubics[rec.cube].cube, corner)];
      for (int c = 0; c < kChannels; ++c) acc[c] += d[c];
    }
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t ch = static_cast<std::size_t>(c);
      const Local& L = rec.ch[ch];
      const double a = adjoint[c];
      to_nodes(L.rho_line, a * L.rho_v0, a * L.rho_beta, a * L.rho_x0, out.density[ch]);
      to_nodes(L.kappa_line, a * L.kappa_v0, a * L.kappa_beta, a * L.kappa_x0, out.color[ch]);
      adjoint[c] *= L.trans;
      if (!jumps) continue;
      // The far end of this piece: a cut inside the cube, a cube face, or the ray's far end.
      const bool inside = k > 0 && pieces[k - 1].cube == rec.cube && rec.knot > 0.0;
      if (!inside) {
        touch(rec.cube, c, rec.f_far, "a cube face or the ray's end");
        if (k > 0) touch(pieces[k - 1].cube, c, pieces[k - 1].f_exit, "a cube face");
        if (k + 1 == pieces.size()) touch(rec.cube, c, rec.f_exit, "the ray's end");
        continue;
      }
      const PieceRecord& before = pieces[k - 1];
      const std::size_t jd = jump_between(tf_->density[ch], before.f_mid, rec.f_mid);
      const std::size_t jc = jump_between(tf_->color[ch], before.f_mid, rec.f_mid);
      if (jd == kNoJump && jc == kNoJump) {
        touch(rec.cube, c, rec.f_far, "a critical point of the cubic");
        continue;
      }
      const double x = jd != kNoJump ? tf_->density[ch].scalar[jd] : tf_->color[ch].scalar[jc];
      if (rec.slope_far == 0.0) {
        touch(rec.cube, c, x, "a point where the cubic is flat");
        continue;
      }
      const Local& B = before.ch[ch];
      const double I_star = rec.light_in[c];
      const double dI_du = adjoint[c] * (B.rho_line.at(x) * (B.kappa_line.at(x) - I_star) -
                                           L.rho_line.at(x) * (L.kappa_line.at(x) - I_star));
      const double per_x = dI_du / rec.slope_far;
      for (int corner = 0; corner < 8; ++corner)
        voxel[trilinear_corner_index(grid, cubics[rec.cube].cube, corner)][c] -=
            per_x * horner(corners[static_cast<std::size_t>(corner)], rec.knot);
      if (jd != kNoJump && jc != kNoJump) {
        out.density[ch][jd].position = out.color[ch][jc].position = std::nan("");
        mark("density and color of one channel jump at one scalar: moving one alone is not differentiable");
        continue;
      }
      (jd != kNoJump ? out.density[ch][jd] : out.color[ch][jc]).position += per_x;
    }
  }
  if (jumps) tie_jump_positions(*tf_, out.density, out.color);
  for (const auto& [cube, c] : nan_cubes)
    for (int corner = 0; corner < 8; ++corner)
      voxel[trilinear_corner_index(grid, cubics[cube].cube, corner)][c] = std::nan("");
  out.background = adjoint;
  for (const auto& [i, d] : voxel) {
    out.index.push_back(i);
    out.d_value.push_back(d);
  }
  return out;
}

}  // namespace rayint
