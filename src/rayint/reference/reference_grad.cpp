// The 50-digit reference gradient: finite differences of the 50-digit ray integral (see
// reference_grad.hpp). Only reference_detail::integrate_piece (the quadrature of Eq. 4 on one
// piece) is shared with reference.cpp; splitting, interpolation and compositing are redone here
// in 50 digits on 50-digit inputs, so that a perturbation of 1e-20 is represented exactly.
#include "rayint/reference/reference_grad.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/core/parallel.hpp"
#include "rayint/reference/reference_detail.hpp"

namespace rayint {
namespace {

using reference_detail::Real;

struct RealFn {
  std::vector<Real> scalar, value;
};

struct RealInputs {
  std::array<RealFn, kChannels> density, color;
  std::vector<Real> length, s_far, s_exit;
};

// f's one-sided limit at s, from above or below (they differ only at a jump: a scalar stored
// twice, left value then right value); a constant segment takes the limit from below, the value
// at the scalar itself (model/transfer_function.hpp).
Real interp(const RealFn& f, const Real& s, bool from_above) {
  const std::vector<Real>& x = f.scalar;
  if (s < x.front() || (s == x.front() && !from_above)) return f.value.front();
  if (s > x.back() || (s == x.back() && from_above)) return f.value.back();
  std::size_t k = 0;  // the line between nodes k - 1 and k
  if (from_above) {   // x[k-1] <= s < x[k]: at a jump the right value (the last node at s)
    k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), s) - x.begin());
    if (s == x[k - 1]) return f.value[k - 1];
  } else {  // x[k-1] < s <= x[k]: at a jump the left value (the first node at s)
    k = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), s) - x.begin());
    if (s == x[k]) return f.value[k];
  }
  const Real& s0 = x[k - 1];
  const Real& s1 = x[k];
  return (f.value[k - 1] * (s1 - s) + f.value[k] * (s - s0)) / (s1 - s0);
}

// Whether f jumps at x (x stored twice).
bool jumps_at(const PiecewiseLinear& f, double x) { return jump_node(f, x) != kNoJump; }

std::vector<Real> breakpoints_of(const RealInputs& in) {
  std::vector<Real> bp;
  for (const auto* group : {&in.density, &in.color})
    for (const RealFn& f : *group) bp.insert(bp.end(), f.scalar.begin(), f.scalar.end());
  std::sort(bp.begin(), bp.end());
  bp.erase(std::unique(bp.begin(), bp.end()), bp.end());
  return bp;
}

// Segment j of channel c: its transmittance and the emission leaving its exit.
struct SegmentOptics {
  Real transmittance = 1;
  Real emission = 0;
};

SegmentOptics segment_optics(const RealInputs& in, const std::vector<Real>& bp, std::size_t j, int c) {
  SegmentOptics out;
  const Real& L = in.length[j];
  if (L == 0) return out;
  const Real& s0 = in.s_far[j];
  const Real& s1 = in.s_exit[j];
  std::vector<Real> ends{s0};
  if (s0 != s1) {
    const Real lo = std::min(s0, s1), hi = std::max(s0, s1);
    for (const Real& b : bp)
      if (lo < b && b < hi) ends.push_back(b);
    if (s0 > s1) std::reverse(ends.begin() + 1, ends.end());
  }
  ends.push_back(s1);
  const Real span = s1 - s0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const Real len = s0 == s1 ? L : L * (ends[k + 1] - ends[k]) / span;
    // Each end from inside the piece: the end with the smaller scalar takes the limit from above.
    const bool far_above = ends[k] < ends[k + 1], exit_above = ends[k + 1] < ends[k];
    const reference_detail::PieceData piece{len, interp(in.density[c], ends[k], far_above),
                                            interp(in.density[c], ends[k + 1], exit_above),
                                            interp(in.color[c], ends[k], far_above),
                                            interp(in.color[c], ends[k + 1], exit_above)};
    const reference_detail::PieceQuadrature q = reference_detail::integrate_piece(piece);
    out.emission = out.emission * q.transmittance + q.emission;
    out.transmittance *= q.transmittance;
  }
  return out;
}

enum class Side { central, forward, backward };

// One parameter: which entry it is, how to perturb it, which channels and segments it moves.
struct Parameter {
  enum Kind { length, s_far, s_exit, node_position, node_value } kind;
  std::size_t segment = 0;  // for length, s_far, s_exit
  bool density = true;      // for nodes: density[c] or color[c]
  int channel = 0;          // for nodes
  std::size_t node = 0;
  Side side = Side::central;
  Real h;
  bool tied = false;  // node_position of a jump's first node: node + 1 (same scalar) moves with it
};

Real& slot(RealInputs& in, const Parameter& p) {
  switch (p.kind) {
    case Parameter::length: return in.length[p.segment];
    case Parameter::s_far: return in.s_far[p.segment];
    case Parameter::s_exit: return in.s_exit[p.segment];
    case Parameter::node_position:
      return (p.density ? in.density : in.color)[p.channel].scalar[p.node];
    case Parameter::node_value:
      return (p.density ? in.density : in.color)[p.channel].value[p.node];
  }
  throw std::logic_error("reference gradient: parameter kind");
}

double to_double(const Real& x) { return static_cast<double>(x); }

}  // namespace

ReferenceGradient reference_gradient(const TransferFunctions& tf, const Ray& ray,
                                     const ReferenceGradientOptions& options) {
  reference_detail::check_transfer_functions(tf);
  for (int c = 0; c < kChannels; ++c)
    if (!std::isfinite(ray.background[c]))
      throw std::invalid_argument("reference gradient: background must be finite");
  RealInputs base;
  for (int c = 0; c < kChannels; ++c) {
    for (const auto& [from, to] : {std::pair{&tf.density[c], &base.density[c]},
                                   std::pair{&tf.color[c], &base.color[c]}}) {
      to->scalar.assign(from->scalar.begin(), from->scalar.end());
      to->value.assign(from->value.begin(), from->value.end());
    }
  }
  const std::size_t m = ray.segments.size();
  for (std::size_t j = 0; j < m; ++j) {
    const Segment& s = ray.segments[j];
    if (!(std::isfinite(s.length) && s.length >= 0 && std::isfinite(s.scalar_far) &&
          std::isfinite(s.scalar_exit)))
      throw std::invalid_argument("reference gradient: segment " + std::to_string(j) +
                                  ": length must be finite and >= 0, scalars finite");
    base.length.emplace_back(s.length);
    base.s_far.emplace_back(s.scalar_far);
    base.s_exit.emplace_back(s.scalar_exit);
  }
  const std::vector<Real> bp = breakpoints_of(base);

  // The unperturbed segments, every channel.
  std::vector<std::array<SegmentOptics, kChannels>> seg(m);
  std::atomic<int> evaluations{0};
  parallel_for(static_cast<long long>(m * kChannels), options.threads, [&](long long i) {
    const auto j = static_cast<std::size_t>(i) / kChannels;
    const int c = static_cast<int>(static_cast<std::size_t>(i) % kChannels);
    seg[j][static_cast<std::size_t>(c)] = segment_optics(base, bp, j, c);
    ++evaluations;
  });
  const auto compose = [&](int c, const std::vector<SegmentOptics>* replaced, std::size_t first_replaced) {
    Real I = ray.background[c];
    for (std::size_t j = 0; j < m; ++j) {
      const SegmentOptics& o = replaced && j >= first_replaced && j - first_replaced < replaced->size()
                                   ? (*replaced)[j - first_replaced]
                                   : seg[j][static_cast<std::size_t>(c)];
      I = I * o.transmittance + o.emission;
    }
    return I;
  };

  ReferenceGradient out;
  out.gradient = RayGradient::zeros(tf, ray);
  for (int c = 0; c < kChannels; ++c) {
    out.gradient.intensity[c] = to_double(compose(c, nullptr, 0));
    Real t = 1;
    for (std::size_t j = 0; j < m; ++j) t *= seg[j][static_cast<std::size_t>(c)].transmittance;
    out.gradient.background[c] = to_double(t);  // I is linear in the background: exact
  }

  // Where I is not smooth in a parameter: a stencil never steps across such a point (its
  // steps are capped at 1/16 of the distance), and a parameter sitting on one takes a one-sided
  // stencil. I is C^1 there (C^0 only at the kink convention's points), but the jump in the
  // second derivative can be huge (slopes of 1e25 in cases/narrow-pulse.json), so a central
  // stencil across it is off by O(h) * that jump.
  const auto on_node = [&](double s) { return std::binary_search(bp.begin(), bp.end(), Real(s)); };
  const Real step = options.step;
  const auto step_for = [&](double x) { return step * Real(std::max(std::fabs(x), 1.0)); };
  // The stencil for x: `forced` one-sided, else central when no kink lies within 16 steps, else
  // one-sided toward the side with more room; the step is capped at 1/16 of the room on the side
  // (or sides) it uses, so that no stencil point crosses a kink.
  const auto stencil = [](Real h, double x, const std::vector<Real>& kinks, Side forced, Side& side) {
    Real left = std::numeric_limits<double>::infinity(), right = left;
    for (const Real& k : kinks) {
      if (k < Real(x)) left = std::min(left, Real(x) - k);
      if (k > Real(x)) right = std::min(right, k - Real(x));
    }
    side = forced;
    if (side == Side::central && std::min(left, right) < 16 * h) side = right >= left ? Side::forward : Side::backward;
    const Real room = side == Side::central ? std::min(left, right) : side == Side::forward ? right : left;
    return std::min(h, room / 16);
  };
  // Kinks in a node position: every other node (breakpoint) and every segment end scalar.
  std::vector<Real> position_kinks = bp;
  for (const Segment& s : ray.segments) {
    position_kinks.emplace_back(s.scalar_far);
    position_kinks.emplace_back(s.scalar_exit);
  }

  std::vector<Parameter> params;
  for (std::size_t j = 0; j < m; ++j) {
    const Segment& s = ray.segments[j];
    if (!(s.length > 0.0)) continue;  // a zero-length segment: derivatives in its scalars are 0
    Parameter p{Parameter::length, j, true, 0, 0, Side::central, step_for(s.length)};
    params.push_back(p);
    for (const auto kind : {Parameter::s_far, Parameter::s_exit}) {
      const double x = kind == Parameter::s_far ? s.scalar_far : s.scalar_exit;
      const double other = kind == Parameter::s_far ? s.scalar_exit : s.scalar_far;
      Side forced = Side::central;
      if (on_node(x)) {
        // Constant scalar: the kink convention (right of the node). Otherwise into the segment,
        // where the piece keeps its interval.
        forced = x == other || other > x ? Side::forward : Side::backward;
      }
      Side side = forced;
      const Real h = stencil(step_for(x), x, bp, forced, side);
      params.push_back({kind, j, true, 0, 0, side, h});
    }
  }
  // The scalars the ray reaches (segments of non-zero length). A node's position and value change
  // f only on [scalar[k-1], scalar[k+1]] (from -inf for the first node, to +inf for the last):
  // a node whose interval the ray never reaches has derivative exactly 0 and is not differenced
  // (an imported ParaView colour map has ~1200 nodes per function). Closed intervals: a node the
  // ray's scalar only touches is differenced.
  double ray_lo = std::numeric_limits<double>::infinity(), ray_hi = -ray_lo;
  for (const Segment& s : ray.segments)
    if (s.length > 0.0) {
      ray_lo = std::min({ray_lo, s.scalar_far, s.scalar_exit});
      ray_hi = std::max({ray_hi, s.scalar_far, s.scalar_exit});
    }
  for (int c = 0; c < kChannels; ++c) {
    for (const bool density : {true, false}) {
      const PiecewiseLinear& f = density ? tf.density[c] : tf.color[c];
      for (std::size_t k = 0; k < f.scalar.size(); ++k) {
        const double x = f.scalar[k];
        const double support_lo = k == 0 ? -std::numeric_limits<double>::infinity() : f.scalar[k - 1];
        // (A jump's first node: its position moves the interval above the jump too.)
        const std::size_t above = k + 1 < f.scalar.size() && f.scalar[k + 1] == x ? k + 2 : k + 1;
        const double support_hi = above >= f.scalar.size() ? std::numeric_limits<double>::infinity() : f.scalar[above];
        if (support_hi < ray_lo || ray_hi < support_lo) continue;
        // A jump's two nodes: the first's position is the jump's (both move: `tied`), the
        // second's entry stays 0 (model/ray_gradient.hpp); their values are ordinary.
        const bool jump_first = k + 1 < f.scalar.size() && f.scalar[k + 1] == x;
        const bool jump_second = k > 0 && f.scalar[k - 1] == x;
        // On another function's node or a segment end: one-sided, backward (for a constant
        // segment there, the kink convention: the interval to the node's right is kept).
        bool coincides = false;
        for (const Segment& s : ray.segments)
          coincides = coincides || (s.length > 0.0 && (s.scalar_far == x || s.scalar_exit == x));
        for (int c2 = 0; c2 < kChannels; ++c2)
          for (const PiecewiseLinear* g : {&tf.density[c2], &tf.color[c2]})
            if (g != &f) coincides = coincides || std::binary_search(g->scalar.begin(), g->scalar.end(), x);
        Side side = Side::central;
        const Real h = stencil(step_for(x), x, position_kinks, coincides ? Side::backward : Side::central, side);
        if (!jump_second) params.push_back({Parameter::node_position, 0, density, c, k, side, h, jump_first});
        const Real hv = step_for(f.value[k]);
        params.push_back({Parameter::node_value, 0, density, c, k,
                          Real(f.value[k]) < 2 * hv ? Side::forward : Side::central, hv});
      }
    }
  }

  struct Result {
    Rgb d{};
    Rgb noise{};
  };
  std::vector<Result> results(params.size());
  parallel_for(static_cast<long long>(params.size()), options.threads, [&](long long pi) {
    const Parameter& p = params[static_cast<std::size_t>(pi)];
    const bool segment_param = p.kind == Parameter::length || p.kind == Parameter::s_far ||
                               p.kind == Parameter::s_exit;
    // Channels and segments it moves.
    std::size_t first = 0, count = m;
    if (segment_param) {
      first = p.segment;
      count = 1;
    }
    Result& r = results[static_cast<std::size_t>(pi)];
    for (int c = 0; c < kChannels; ++c) {
      if (!segment_param && c != p.channel) continue;
      const auto value_at = [&](int offset) {
        if (offset == 0) return compose(c, nullptr, 0);
        RealInputs in = base;
        slot(in, p) += p.h * offset;
        if (p.tied) (p.density ? in.density : in.color)[p.channel].scalar[p.node + 1] += p.h * offset;
        const std::vector<Real> bp2 = segment_param ? bp : breakpoints_of(in);
        std::vector<SegmentOptics> rep(count);
        for (std::size_t q = 0; q < count; ++q) {
          rep[q] = segment_optics(in, bp2, first + q, c);
          ++evaluations;
        }
        return compose(c, &rep, first);
      };
      Real d4, d2;
      if (p.side == Side::central) {
        const Real f1 = value_at(1), fm1 = value_at(-1), f2 = value_at(2), fm2 = value_at(-2);
        d4 = (8 * (f1 - fm1) - (f2 - fm2)) / (12 * p.h);
        d2 = (f1 - fm1) / (2 * p.h);
      } else {
        const int dir = p.side == Side::forward ? 1 : -1;
        const Real f0 = value_at(0), f1 = value_at(dir), f2 = value_at(2 * dir), f3 = value_at(3 * dir),
                   f4 = value_at(4 * dir);
        d4 = (-25 * f0 + 48 * f1 - 36 * f2 + 16 * f3 - 3 * f4) / (12 * p.h * dir);
        d2 = (-3 * f0 + 4 * f1 - f2) / (2 * p.h * dir);
      }
      r.d[c] = to_double(d4);
      r.noise[c] = to_double(abs(d4 - d2));
    }
  });

  for (std::size_t i = 0; i < params.size(); ++i) {
    const Parameter& p = params[i];
    const Result& r = results[i];
    RayGradient& g = out.gradient;
    for (int c = 0; c < kChannels; ++c) out.noise[c] = std::max(out.noise[c], r.noise[c]);
    switch (p.kind) {
      case Parameter::length: g.length[p.segment] = r.d; break;
      case Parameter::s_far: g.scalar_far[p.segment] = r.d; break;
      case Parameter::s_exit: g.scalar_exit[p.segment] = r.d; break;
      case Parameter::node_position:
        (p.density ? g.density : g.color)[p.channel][p.node].position = r.d[p.channel];
        break;
      case Parameter::node_value:
        (p.density ? g.density : g.color)[p.channel][p.node].value = r.d[p.channel];
        break;
    }
  }
  // Derivatives that do not exist (model/ray_gradient.hpp), decided from the inputs: where a
  // segment end (of non-zero length) lies on a jump of density[c] or color[c], that end's scalar
  // and the jump's position, in channel c; where density[c] and color[c] jump at one scalar that
  // a segment reaches, both positions.
  RayGradient& g = out.gradient;
  const auto mark = [&g](const std::string& why) {
    if (!g.undefined.empty()) g.undefined += "; ";
    g.undefined += why;
  };
  for (int c = 0; c < kChannels; ++c) {
    const auto cs = static_cast<std::size_t>(c);
    for (std::size_t j = 0; j < m; ++j) {
      const Segment& s = ray.segments[j];
      if (!(s.length > 0.0)) continue;
      for (const bool density : {true, false}) {
        const PiecewiseLinear& f = density ? tf.density[cs] : tf.color[cs];
        for (const bool far : {true, false}) {
          const double x = far ? s.scalar_far : s.scalar_exit;
          if (!jumps_at(f, x)) continue;
          (far ? g.scalar_far : g.scalar_exit)[j][cs] = std::nan("");
          (density ? g.density : g.color)[cs][jump_node(f, x)].position = std::nan("");
          mark("segment " + std::to_string(j) + " ends on a jump");
        }
      }
      for (std::size_t k = 0; k + 1 < tf.density[cs].scalar.size(); ++k) {
        const double x = tf.density[cs].scalar[k];
        if (tf.density[cs].scalar[k + 1] != x || !jumps_at(tf.color[cs], x)) continue;
        if (std::min(s.scalar_far, s.scalar_exit) <= x && x <= std::max(s.scalar_far, s.scalar_exit)) {
          g.density[cs][k].position = std::nan("");
          g.color[cs][jump_node(tf.color[cs], x)].position = std::nan("");
          mark("density and color jump at one scalar");
        }
      }
    }
  }
  out.evaluations = evaluations.load();
  return out;
}

}  // namespace rayint
