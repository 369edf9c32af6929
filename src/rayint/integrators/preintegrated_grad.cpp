// preintegrated_grad.cpp -- the gradient of the pre-integrated renderer (preintegrated.cpp):
// what automatic differentiation through that renderer computes (issue 28, "gradients of the
// tables"), by reverse-mode differentiation of its steps, lookups and table build in double.
//
// Forward (integrate()'s, one cut: PreintegratedIntegrator::for_each_step): per step of a
// segment, scalars s0 (far), s1 (exit) and length l, with s0, s1, l linear in the segment's end
// scalars and (dims = 2) its length; per channel
//     rate = bilerp(rate table; x0, x1),  q = bilerp(q table; x0, x1) [lerp over planes in l],
//     tau = rate l,  transmittance e^{-tau},  emission q l phi(tau),  phi = step_weight,
// with the grid coordinates x = (s - s_lo) (size - 1)/(s_hi - s_lo) clamped to the table, and
// the steps composited far -> near onto the background. The forward intensity is integrate()'s,
// bit for bit (the same lookups, the compensated depth sum for the background term).
//
// Reverse, per step and channel (adjoint a = transmittance of everything nearer, I_in the light
// entering the step):
//     d/d tau = -a I_in e^{-tau} + a q l phi'(tau),   d/dq = a l phi(tau),
//     d/dl   += a q phi(tau) + (d/d tau) rate,          d/d rate = (d/d tau) l,
// then through the lookups:
//   - linear lookup: the derivative of the bilinear interpolant of the cell locate() picked,
//     d/dx = difference of the cell's rows or columns (one-sided, from the cell to the right, at
//     a grid line, where the interpolant has a kink), dx/ds = (size-1)/(s_hi - s_lo) inside the
//     table and 0 where the coordinate is clamped (scalars outside [s_lo, s_hi]: autodiff through
//     a clamp); dims = 3, d q/d l from the lerp between the two planes (0 where clamped);
//   - nearest and floor: piecewise constant, every derivative through a coordinate is 0;
//   and to the four (nearest: one) table entries with the bilinear weights.
// Through the table build (the adjoint of every entry a ray read), entry (i, j) being the step of
// unit length from grid scalar g_i to g_j (constructor of preintegrated.cpp):
//     rate = int_0^1 rho du      -> d rate = sum over pieces len (d rho_far + d rho_exit)/2,
//     q(L) = E(L) / (L phi(rate L)), L > 0
//                                -> d q = dE / (L phi) - q L phi'(rate L) d rate / phi,
//     q(0) = int_0^1 kappa rho du -> d q = sum over pieces len/6 [(2 rho_f + rho_e) d kappa_f
//                                   + (rho_f + 2 rho_e) d kappa_e + (2 kappa_f + kappa_e) d rho_f
//                                   + (kappa_f + 2 kappa_e) d rho_e],
//   with d rho, d kappa at a piece end from node_weights (value and position of the nodes of its
//   interval; the interval to the right of a node at the piece's lower end) and dE the exact
//   gradient of the one-segment ray {L, g_i -> g_j} on a black background (exact_ray_gradient,
//   its density and color blocks). Moving a breakpoint moves the piece ends too, but the
//   integrands are continuous there, so those terms cancel (Leibniz); the sums above are the
//   full first derivative of the table entry with respect to the node.
// Jumps (a node scalar stored twice): the table build splits each entry's unit step at the jump
// (append_pieces) and integrates each side with its own one-sided limits, so an entry is a smooth
// function of the jump's position while the jump lies strictly between the entry's two grid
// scalars: the piece terms above (values of each side, node positions of the linear pieces
// beside the jump), plus the boundary term of the moving switch point, (integrand(x-) -
// integrand(x+)) / |g_j - g_i| for rate and q(0) (add_entry_jump_terms), and exact_ray_gradient's
// crossing term for E(L). The lookups are bilinear in the entries, so the renderer is as smooth
// in the nodes as its entries are. Where a grid scalar lies exactly on the jump (always the case
// for a jump at the range's first or last breakpoint) the entries that start or end there are
// one-sided in its position: NaN, with `undefined` saying why. The position entries follow the
// tie of model/ray_gradient.hpp. Measured: against central differences of this renderer's own
// intensity across jumps (tests/test_grad_jumps.cpp, 5 configurations, 15 ray-channels): 5.5e-10
// of the channel's largest entry, the differences' own error.
// What is not differentiated: the table's scalar range [s_lo, s_hi] = [first, last breakpoint
// of the six functions] is held fixed. It moves with the position of the extreme node, but it is
// a min/max over all six functions' nodes -- not differentiable where several functions share
// the end node, the common case (every preset and case starts its functions at one scalar) --
// and the per-channel layout of RayGradient has no entry for a node of another channel's
// function that sets it. So the derivative reported for the position of a node at s_lo or s_hi
// is the one with the grid held in place (the node's effect through the table entries only).
// The step count per segment (a ceil) and the clamp of the plane coordinate are piecewise
// constant, as for autodiff.
//
// Cost: the forward lookups plus, per distinct table entry a ray read, one exact gradient of a
// one-segment ray per plane it was read from (shared by the three channels); a study tool, not
// a renderer's inner loop.
// Accuracy: tests/test_preintegrated_grad.cpp ([preintegrated_grad]) against central differences
// of the renderer itself (table rebuilt for every node perturbation) and against the 50-digit
// reference gradient as the size grows; figures in reports/gradients/.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "rayint/core/math.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/preintegrated.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

// d/dx of step_weight(x) = (1 - e^{-x})/x (core/math.hpp): (e^{-x} - step_weight(x))/x, -1/2 at
// x = 0. x < 0.5: its Maclaurin series sum_{k>=1} (-1)^k k x^{k-1}/(k+1)! to k = 18 (the next
// term is below 1e-20 there; the difference form loses up to 16 digits near 0); x >= 0.5: the
// difference form, which loses under one digit there (|e^{-x} - phi| >= 0.18 phi).
double step_weight_derivative(double x) {
  if (x >= 0.5) return (std::exp(-x) - step_weight(x)) / x;
  double inverse_factorial = 1.0;  // 1/(k+1)!, from k = 18 down
  for (int i = 2; i <= 19; ++i) inverse_factorial /= i;
  double sum = 0.0;
  for (int k = 18; k >= 1; --k) {  // Horner form
    sum = sum * x + (k % 2 ? -1.0 : 1.0) * k * inverse_factorial;
    inverse_factorial *= k + 1;
  }
  return sum;
}

// d/dx of table::locate's coordinate: 1 inside the table under linear lookup, 0 where clamped
// (x <= 0 or x > top, locate's own tests) and for nearest/floor (piecewise constant).
double coordinate_slope(double x, int n, table::Lookup lookup) {
  if (lookup != table::Lookup::linear) return 0.0;
  return (x > 0.0 && !(x > n - 1)) ? 1.0 : 0.0;
}

// A bilinear read with its derivatives: value, d/d row weight, d/d column weight, and the
// entries and weights it reads (up to four).
struct Bilinear {
  double value = 0.0, d_row = 0.0, d_col = 0.0;
  std::size_t entry[4] = {0, 0, 0, 0};
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
  int count = 0;
};

Bilinear bilinear(const double* v, int n, const table::GridCoord& r, const table::GridCoord& c,
                  bool linear) {
  Bilinear b;
  const std::size_t base = static_cast<std::size_t>(r.i) * n + c.i;
  b.value = table::bilerp(v, n, r, c);  // the renderer's value, bit for bit
  if (!linear) {
    b.entry[0] = base;
    b.weight[0] = 1.0;
    b.count = 1;
    return b;
  }
  // locate() under linear lookup always leaves i + 1 inside the table.
  const std::size_t below = base + static_cast<std::size_t>(n);
  const double v00 = v[base], v01 = v[base + 1], v10 = v[below], v11 = v[below + 1];
  const double top = (1.0 - c.w) * v00 + c.w * v01, bottom = (1.0 - c.w) * v10 + c.w * v11;
  b.d_row = bottom - top;
  b.d_col = (1.0 - r.w) * (v01 - v00) + r.w * (v11 - v10);
  b.count = 4;
  b.entry[0] = base;
  b.entry[1] = base + 1;
  b.entry[2] = below;
  b.entry[3] = below + 1;
  b.weight[0] = (1.0 - r.w) * (1.0 - c.w);
  b.weight[1] = (1.0 - r.w) * c.w;
  b.weight[2] = r.w * (1.0 - c.w);
  b.weight[3] = r.w * c.w;
  return b;
}

// Adds bar * d f(s) into the node blocks of f (value and position), s at a piece end whose
// interval is chosen by the piece's lower scalar `lo`.
void add_node_derivative(const PiecewiseLinear& f, double lo, double s, double bar,
                         std::vector<NodeDerivative>& nodes) {
  if (bar == 0.0) return;
  const NodeWeights nw = node_weights(f, lo, s);
  for (int q = 0; q < nw.count; ++q) {
    nodes[nw.node[q]].value += bar * nw.w[q];
    nodes[nw.node[q]].position += bar * nw.dp[q];
  }
}

// The boundary terms of a table entry's integrals at the jumps it crosses (see the header
// comment, "Jumps"): the entry is the unit step from grid scalar gi to gj, its integrand
// rho (rate) or kappa rho (q(0), with_kappa) switches at every jump x strictly between them, at
// the fraction u* = (x - gi)/(gj - gi) of the step, so
//     d/dx int_0^1 integrand du = (integrand(x-) - integrand(x+)) / |gj - gi|
// (moving x up turns a slab of width 1/|gj - gi| per unit of x from right to left values, in
// either direction of the step), into the first node's position entry (the tie). A grid point
// exactly on x (gi == x or gj == x) makes the entry one-sided in x: NaN, as where density[c] and
// color[c] both jump at x in q(0) (moving one alone is one-sided).
void add_entry_jump_terms(const TransferFunctions& tf, int c, double gi, double gj, double bar, bool with_kappa,
                          RayGradient& g) {
  if (bar == 0.0) return;
  const double lo = std::min(gi, gj), hi = std::max(gi, gj);
  for (const bool density : {true, false}) {
    if (!density && !with_kappa) continue;
    const PiecewiseLinear& f = density ? tf.density[c] : tf.color[c];
    const PiecewiseLinear& other = density ? tf.color[c] : tf.density[c];
    std::vector<NodeDerivative>& nodes = density ? g.density[c] : g.color[c];
    for (std::size_t i = 0; i + 1 < f.scalar.size(); ++i) {
      const double x = f.scalar[i];
      if (x != f.scalar[i + 1] || x < lo || x > hi) continue;
      const bool both = with_kappa && jump_node(other, x) != kNoJump;
      if (x == gi || x == gj || both) {
        nodes[i].position = std::nan("");
        const std::string why = std::string("preintegrated: a table entry read ") +
                                (both ? "crosses jumps of density and color at one scalar "
                                      : "has a grid scalar on the jump at ") +
                                std::to_string(x) + " (one-sided in the jump's position)";
        // Said once per jump, however many entries the ray reads there.
        if (g.undefined.find(why) == std::string::npos) g.undefined += (g.undefined.empty() ? "" : "; ") + why;
        continue;
      }
      const auto integrand = [&](bool above) {
        return with_kappa ? tf.density[c].limit(x, above) * tf.color[c].limit(x, above) : tf.density[c].limit(x, above);
      };
      nodes[i].position += bar * (integrand(false) - integrand(true)) / (hi - lo);
    }
  }
}

}  // namespace

RayGradient PreintegratedIntegrator::gradient(const TransferFunctions& tf, const Ray& ray) const {
  count_lookups(ray);
  const int n = opt_.size;
  const bool linear = opt_.lookup == table::Lookup::linear;
  const int plane_count = static_cast<int>(plane_length_.size());

  struct StepRecord {
    Cut cut;
    table::GridCoord row, col, plane;
    double slope_row = 0.0, slope_col = 0.0, slope_plane = 0.0;  // d coordinate / d (s0, s1, l)
    Bilinear rate[kChannels], q_low[kChannels], q_high[kChannels];
    double incoming[kChannels] = {0.0, 0.0, 0.0};
    double transmittance[kChannels] = {0.0, 0.0, 0.0};
  };
  std::vector<StepRecord> steps;
  Rgb emission{0.0, 0.0, 0.0}, light = ray.background, depth{0.0, 0.0, 0.0}, depth_carry{0.0, 0.0, 0.0};
  for_each_step(ray, [&](const Cut& cut) {
    StepRecord st;
    st.cut = cut;
    const double x_row = (cut.s0 - s_lo_) * inv_ds_, x_col = (cut.s1 - s_lo_) * inv_ds_;
    st.row = table::locate(x_row, n, opt_.lookup);
    st.col = table::locate(x_col, n, opt_.lookup);
    st.slope_row = coordinate_slope(x_row, n, opt_.lookup) * inv_ds_;
    st.slope_col = coordinate_slope(x_col, n, opt_.lookup) * inv_ds_;
    if (opt_.dims == 3) {
      const double x_plane = cut.l * inv_dL_;
      st.plane = table::locate(x_plane, plane_count, opt_.lookup);
      st.slope_plane = coordinate_slope(x_plane, plane_count, opt_.lookup) * inv_dL_;
    }
    const StepOptics o = lookup(cut.s0, cut.s1, cut.l);  // the renderer's optics, bit for bit
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t k = static_cast<std::size_t>(st.plane.i) * kChannels + static_cast<std::size_t>(c);
      st.rate[c] = bilinear(rate_[c].data(), n, st.row, st.col, linear);
      st.q_low[c] = bilinear(q_[k].data(), n, st.row, st.col, linear);
      if (opt_.dims == 3 && linear) st.q_high[c] = bilinear(q_[k + kChannels].data(), n, st.row, st.col, linear);
      st.incoming[c] = light[c];
      st.transmittance[c] = o.transmittance[c];
      light[c] = light[c] * o.transmittance[c] + o.emission[c];
      emission[c] = emission[c] * o.transmittance[c] + o.emission[c];
      const double sum = depth[c] + o.depth[c];
      depth_carry[c] += std::fabs(depth[c]) >= std::fabs(o.depth[c]) ? (depth[c] - sum) + o.depth[c]
                                                                     : (o.depth[c] - sum) + depth[c];
      depth[c] = sum;
    }
    steps.push_back(st);
  });

  RayGradient g = RayGradient::zeros(tf, ray);
  for (int c = 0; c < kChannels; ++c)
    g.intensity[c] = ray.background[c] * std::exp(-(depth[c] + depth_carry[c])) + emission[c];

  // Adjoints of the table entries a ray read: key (plane, entry); plane -1 is the rate table.
  std::map<std::pair<int, std::size_t>, Rgb> entry_bar;
  const auto add_entries = [&](int plane, const Bilinear& b, int c, double bar) {
    if (bar == 0.0) return;
    for (int e = 0; e < b.count; ++e)
      if (b.weight[e] != 0.0) entry_bar[{plane, b.entry[e]}][c] += bar * b.weight[e];
  };
  Rgb adjoint{1.0, 1.0, 1.0};
  for (std::size_t k = steps.size(); k-- > 0;) {
    const StepRecord& st = steps[k];
    const Cut& cut = st.cut;
    double s0_bar[kChannels] = {}, s1_bar[kChannels] = {}, l_bar[kChannels] = {};
    for (int c = 0; c < kChannels; ++c) {
      const double rate = st.rate[c].value;
      const double w = st.plane.w;
      const double q = opt_.dims == 3 && linear ? (1.0 - w) * st.q_low[c].value + w * st.q_high[c].value
                                                : st.q_low[c].value;
      const double tau = rate * cut.l;
      const double phi = step_weight(tau);
      const double a = adjoint[c];
      const double tau_bar = -a * st.incoming[c] * st.transmittance[c] + a * q * cut.l * step_weight_derivative(tau);
      const double q_bar = a * cut.l * phi;
      const double rate_bar = tau_bar * cut.l;
      l_bar[c] = a * q * phi + tau_bar * rate;
      // rate and q through the coordinates.
      double d_row = rate_bar * st.rate[c].d_row, d_col = rate_bar * st.rate[c].d_col;
      if (opt_.dims == 3 && linear) {
        d_row += q_bar * ((1.0 - w) * st.q_low[c].d_row + w * st.q_high[c].d_row);
        d_col += q_bar * ((1.0 - w) * st.q_low[c].d_col + w * st.q_high[c].d_col);
        l_bar[c] += q_bar * (st.q_high[c].value - st.q_low[c].value) * st.slope_plane;
      } else {
        d_row += q_bar * st.q_low[c].d_row;
        d_col += q_bar * st.q_low[c].d_col;
      }
      s0_bar[c] = d_row * st.slope_row;
      s1_bar[c] = d_col * st.slope_col;
      // ... and to the entries read.
      add_entries(-1, st.rate[c], c, rate_bar);
      if (opt_.dims == 3 && linear) {
        add_entries(st.plane.i, st.q_low[c], c, q_bar * (1.0 - w));
        add_entries(st.plane.i + 1, st.q_high[c], c, q_bar * w);
      } else {
        add_entries(st.plane.i, st.q_low[c], c, q_bar);
      }
      adjoint[c] *= st.transmittance[c];
    }
    for (int c = 0; c < kChannels; ++c) {
      g.scalar_far[cut.segment][c] += s0_bar[c] * cut.s0_far + s1_bar[c] * cut.s1_far;
      g.scalar_exit[cut.segment][c] += s0_bar[c] * cut.s0_exit + s1_bar[c] * cut.s1_exit;
      g.length[cut.segment][c] += l_bar[c] * cut.l_length + s0_bar[c] * cut.s0_length + s1_bar[c] * cut.s1_length;
    }
  }
  g.background = adjoint;

  // Through the table build, entry by entry.
  const std::vector<double> breakpoints = tf.breakpoints();
  const bool jumps = tf.has_jump();
  std::vector<Piece> pieces;
  RayGradient entry_grad;
  for (const auto& [key, bar] : entry_bar) {
    const auto [plane, entry] = key;
    const int i = static_cast<int>(entry / static_cast<std::size_t>(n));
    const int j = static_cast<int>(entry % static_cast<std::size_t>(n));
    const double gi = grid_scalar(i), gj = grid_scalar(j);
    pieces.clear();
    append_pieces(tf, Segment{1.0, gi, gj}, breakpoints, pieces);
    // d rate (plane -1 directly; a q plane of L > 0 through phi(rate L)) and d q(0).
    const auto through_rate = [&](int c, double rate_bar) {
      if (jumps) add_entry_jump_terms(tf, c, gi, gj, rate_bar, false, g);
      for (const Piece& p : pieces) {
        const double lo = std::min(p.scalar_far, p.scalar_exit);
        add_node_derivative(tf.density[c], lo, p.scalar_far, rate_bar * 0.5 * p.length, g.density[c]);
        add_node_derivative(tf.density[c], lo, p.scalar_exit, rate_bar * 0.5 * p.length, g.density[c]);
      }
    };
    if (plane < 0) {
      for (int c = 0; c < kChannels; ++c) through_rate(c, bar[c]);
      continue;
    }
    const double L = plane_length_[static_cast<std::size_t>(plane)];
    if (!(L > 0.0)) {  // q(0) = int kappa rho du
      for (int c = 0; c < kChannels; ++c) {
        if (bar[c] == 0.0) continue;
        if (jumps) add_entry_jump_terms(tf, c, gi, gj, bar[c], true, g);
        for (const Piece& p : pieces) {
          const double lo = std::min(p.scalar_far, p.scalar_exit);
          const double rf = p.rho_far[c], re = p.rho_exit[c], kf = p.kappa_far[c], ke = p.kappa_exit[c];
          const double w = bar[c] * p.length / 6.0;
          add_node_derivative(tf.color[c], lo, p.scalar_far, w * (2.0 * rf + re), g.color[c]);
          add_node_derivative(tf.color[c], lo, p.scalar_exit, w * (rf + 2.0 * re), g.color[c]);
          add_node_derivative(tf.density[c], lo, p.scalar_far, w * (2.0 * kf + ke), g.density[c]);
          add_node_derivative(tf.density[c], lo, p.scalar_exit, w * (kf + 2.0 * ke), g.density[c]);
        }
      }
      continue;
    }
    Ray unit;
    unit.segments.push_back(Segment{L, gi, gj});
    exact_ray_gradient(tf, unit, entry_grad);  // background 0: the intensity is E(L)
    if (!entry_grad.undefined.empty() && g.undefined.find(entry_grad.undefined) == std::string::npos)
      g.undefined += (g.undefined.empty() ? "preintegrated: a table entry read: " : "; preintegrated: a table entry read: ") +
                     entry_grad.undefined;
    for (int c = 0; c < kChannels; ++c) {
      if (bar[c] == 0.0) continue;
      const double rate = rate_[c][entry];
      const double q = q_[static_cast<std::size_t>(plane) * kChannels + static_cast<std::size_t>(c)][entry];
      const double phi = step_weight(rate * L);
      const double e_bar = bar[c] / (L * phi);  // dq/dE
      for (std::size_t k = 0; k < g.density[c].size(); ++k) {
        g.density[c][k].value += e_bar * entry_grad.density[c][k].value;
        g.density[c][k].position += e_bar * entry_grad.density[c][k].position;
      }
      for (std::size_t k = 0; k < g.color[c].size(); ++k) {
        g.color[c][k].value += e_bar * entry_grad.color[c][k].value;
        g.color[c][k].position += e_bar * entry_grad.color[c][k].position;
      }
      through_rate(c, -bar[c] * q * L * step_weight_derivative(rate * L) / phi);
    }
  }
  // A jump's two position entries: the derivative for moving both, on the first (the node
  // terms of the pieces either side landed on both nodes; exact_ray_gradient's are tied already).
  if (jumps) tie_jump_positions(tf, g.density, g.color);
  return g;
}

}  // namespace rayint
