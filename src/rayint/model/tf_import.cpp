// VTK transfer functions as rayint's piecewise-linear ones (what is exact, what is linearised and
// how the deviation is measured: tf_import.hpp). The adaptive linearisation bisects an interval
// until the chord is within the absolute tolerance everywhere on it, with a budget of kMaxDepth
// bisections (an interval of width 2^-48 of the original; a function that still deviates there,
// i.e. one with a jump, is accepted and reported as not converged).
// "Everywhere": the error curve e_j(x) = |curve_j(x) - chord_j(x)| of each channel is sampled at
// kProbes equally spaced interior points, and every sampled local maximum is then refined by
// Brent's method (boost::math::tools::brent_find_minima on -e_j) on the bracket of its two
// neighbouring probes. Sampling alone missed maxima: with 16 probes and no refinement, 23 of
// ParaView 5.11's built-in presets exceeded 1e-6 between probes (up to 1.003e-6, issue 27); the
// test "[paraview]" checks the refined bound against VTK's own colours at ~600 scalars a preset.
#include "rayint/model/tf_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>

#include <boost/math/tools/minima.hpp>

#include "rayint/core/limits.hpp"

namespace rayint {
namespace {

constexpr int kProbes = 16;
// Brent's method: location to 2^-30 of the bracket (the error is flat at its maximum, so its
// value is then exact to ~2^-60 relative), at most 64 evaluations per maximum.
constexpr int kBrentBits = 30;
constexpr std::uintmax_t kBrentIterations = 64;
constexpr int kMaxDepth = 48;

using Values = std::array<double, 3>;
using Curve = std::function<Values(double)>;

// Points of n (1 or 3) piecewise-linear functions on one strictly increasing set of scalars.
class Builder {
 public:
  // The node budget (core/limits.hpp kTransferNodes) is read once, before any node is made.
  Builder(int n, double tolerance) : n_(n), max_nodes_(limits::value(limits::kTransferNodes)) {
    report_.tolerance = tolerance;
  }

  void push(double x, const Values& v) {
    if (!x_.empty() && !(x > x_.back())) return;  // a node repeated (a step at an interval's end)
    if (x_.size() >= max_nodes_)
      throw std::length_error("the linearisation needs more than " + std::to_string(max_nodes_) +
                              " nodes (RAYINT_MAX_TF_NODES=N raises the limit; docs/limits.md)");
    x_.push_back(x);
    v_.push_back(v);
  }
  // A jump at the last node's scalar: the function is v just above it (the node keeps its value,
  // the left one). Two jumps at one scalar keep the last right value (a scalar stays at most
  // twice in a row, as PiecewiseLinear requires).
  // A difference at rounding level (<= kJumpFloor in every component: an HSV round trip at a
  // node, 5e-17 measured) is not a jump: the curve keeps its node value, 1e-12 inside the
  // import's 1e-6 tolerance, and stays continuous (gradients refuse jumps).
  void jump(const Values& v) {
    constexpr double kJumpFloor = 1e-12;
    bool tiny = true;
    for (std::size_t c = 0; c < v.size(); ++c) tiny = tiny && std::fabs(v[c] - v_.back()[c]) <= kJumpFloor;
    if (tiny) return;
    if (x_.size() >= 2 && x_[x_.size() - 2] == x_.back()) {
      v_.back() = v;
      return;
    }
    if (x_.size() >= max_nodes_)
      throw std::length_error("the linearisation needs more than " + std::to_string(max_nodes_) +
                              " nodes (RAYINT_MAX_TF_NODES=N raises the limit; docs/limits.md)");
    x_.push_back(x_.back());
    v_.push_back(v);
  }
  double last_x() const { return x_.back(); }
  const Values& last_value() const { return v_.back(); }

  // The chord from the last point to (b, vb), refined until it follows `curve`.
  void adaptive(const Curve& curve, double b, const Values& vb) {
    ++report_.adaptive_intervals;
    refine(curve, x_.back(), v_.back(), b, vb, 0);
  }
  void exact_interval() { ++report_.exact_intervals; }

  LinearisationReport finish(std::array<PiecewiseLinear, kChannels>& out) {
    for (int j = 0; j < kChannels; ++j) {
      out[j].scalar = x_;
      out[j].value.resize(v_.size());
      for (std::size_t i = 0; i < v_.size(); ++i) out[j].value[i] = v_[i][n_ == 1 ? 0 : j];
    }
    report_.nodes = x_.size();
    return report_;
  }

 private:
  // The largest |curve_j - chord_j| over (a, b), all channels: probes, then Brent from each
  // sampled local maximum.
  double max_deviation(const Curve& curve, double a, const Values& va, double b, const Values& vb) const {
    // The chord as PiecewiseLinear evaluates it (from the nearer end).
    auto error = [&](int j, double x, const Values& g) {
      const double d0 = x - a, d1 = b - x, span = b - a;
      const double chord = d0 <= d1 ? va[j] + (d0 / span) * (vb[j] - va[j]) : vb[j] + (d1 / span) * (va[j] - vb[j]);
      return std::fabs(g[j] - chord);
    };
    std::array<double, kProbes + 2> x{};
    std::array<Values, kProbes + 2> e{};  // e[0] and e[kProbes + 1]: the ends, where the chord is exact
    x[0] = a;
    x[kProbes + 1] = b;
    double dev = 0.0;
    for (int k = 1; k <= kProbes; ++k) {
      x[k] = a + (b - a) * k / (kProbes + 1);
      const Values g = curve(x[k]);
      for (int j = 0; j < n_; ++j) dev = std::max(dev, e[k][j] = error(j, x[k], g));
    }
    for (int j = 0; j < n_; ++j)
      for (int k = 1; k <= kProbes; ++k) {
        if (!(e[k][j] > 0.0 && e[k][j] >= e[k - 1][j] && e[k][j] >= e[k + 1][j])) continue;
        std::uintmax_t iterations = kBrentIterations;
        const auto found = boost::math::tools::brent_find_minima(
            [&](double t) { return -error(j, t, curve(t)); }, x[k - 1], x[k + 1], kBrentBits, iterations);
        dev = std::max(dev, -found.second);
      }
    return dev;
  }

  void refine(const Curve& curve, double a, const Values& va, double b, const Values& vb, int depth) {
    const double dev = max_deviation(curve, a, va, b, vb);
    const double mid = a + (b - a) / 2;
    if (dev <= report_.tolerance || depth >= kMaxDepth || !(mid > a && mid < b)) {
      if (dev > report_.tolerance) report_.converged = false;
      report_.max_deviation = std::max(report_.max_deviation, dev);
      push(b, vb);
      return;
    }
    const Values vm = curve(mid);
    refine(curve, a, va, mid, vm, depth + 1);
    refine(curve, mid, vm, b, vb, depth + 1);
  }

  int n_;
  std::size_t max_nodes_;
  std::vector<double> x_;
  std::vector<Values> v_;
  LinearisationReport report_;
};

// One function's intervals: node values, each interval's shape and its curve.
struct Intervals {
  std::size_t count_nodes;
  std::function<double(std::size_t)> x;
  std::function<IntervalShape(std::size_t)> shape;  // of interval k
  std::function<double(std::size_t)> midpoint;      // of interval k
  std::function<StepLocation(std::size_t)> step;    // of a step interval k
  std::function<Values(std::size_t, double)> value; // interval k's curve (converted)
  std::function<Values(std::size_t)> left_value;    // interval k's left node value (step)
  std::function<Values(std::size_t)> right_value;   // interval k's right node value (step)
  std::function<Values(double)> at;                 // VTK's value at x (converted)
  bool linear_map = true;  // the conversion keeps straight pieces straight
};

// Where VTK's value first leaves `value` above the node at x: the next double, or under a log scale,
// where VTK locates 10^(log10 y) past the node, up to 64 doubles later.
double first_change(const Intervals& f, double x, const Values& value) {
  double y = std::nextafter(x, std::numeric_limits<double>::infinity());
  for (int i = 0; i < 64 && f.at(y) == value; ++i) y = std::nextafter(y, std::numeric_limits<double>::infinity());
  return f.at(y) == value ? std::nextafter(x, std::numeric_limits<double>::infinity()) : y;
}

void linearise(const Intervals& f, Builder& out) {
  const std::size_t n = f.count_nodes;
  out.push(f.x(0), f.at(f.x(0)));
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double x1 = f.x(k), x2 = f.x(k + 1);
    // A repeated scalar (duplicate nodes): no interval; the next one's start carries the jump.
    if (!(x2 > x1)) continue;
    const Curve curve = [&f, k](double x) { return f.value(k, x); };
    // VTK's value at x1 belongs to interval k-1 (or is node 0's own); interval k starts from its
    // own right limit: a jump at x1 when the two differ (under a log scale at the last double
    // where VTK still has the old value, a few doubles later).
    const Values start = f.value(k, x1);
    if (start != out.last_value()) {
      const double at = std::nextafter(first_change(f, x1, out.last_value()), -std::numeric_limits<double>::infinity());
      if (at < x2) {
        if (at > out.last_x()) out.push(at, out.last_value());
        out.jump(start);
      }
    }
    const IntervalShape shape = f.shape(k);
    if (shape == IntervalShape::step) {
      const StepLocation step = f.step(k);
      out.push(step.below, f.left_value(k));
      out.jump(f.right_value(k));  // at step.below: step.above is the next double
      out.push(x2, f.at(x2));
      out.exact_interval();
    } else if (shape == IntervalShape::linear && f.linear_map) {
      out.push(x2, f.at(x2));
      out.exact_interval();
    } else if (shape == IntervalShape::two_linear_pieces && f.linear_map) {
      const double xm = midpoint_scalar(x1, x2, f.midpoint(k));
      out.push(xm, curve(xm));
      out.push(x2, f.at(x2));
      out.exact_interval();
    } else if (shape == IntervalShape::two_linear_pieces || shape == IntervalShape::linear) {
      // Straight in opacity, curved in density (sample_distance): refine each straight piece, so
      // the kink at the midpoint is a node.
      const double xm = midpoint_scalar(x1, x2, f.midpoint(k));
      if (shape == IntervalShape::two_linear_pieces && xm > out.last_x() && xm < x2)
        out.adaptive(curve, xm, curve(xm));
      out.adaptive(curve, x2, f.at(x2));
    } else {
      out.adaptive(curve, x2, f.at(x2));
    }
  }
  // Beyond the last node VTK returns the node's stored value, which the last interval's curve
  // need not end on (Lab, HSV, Diverging round-trip it: Cool to Warm's green by 1.3e-4): a jump
  // one double after the last node (a few under a log scale), as at the first.
  const Values beyond = f.at(std::numeric_limits<double>::max());  // the clamped end value
  if (n > 1 && beyond != out.last_value()) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    double y = std::nextafter(f.x(n - 1), inf);
    for (int i = 0; i < 64 && f.at(y) != beyond; ++i) y = std::nextafter(y, inf);
    if (f.at(y) != beyond) y = std::nextafter(f.x(n - 1), inf);
    // The curve's own values up to the double before (a few doubles past s = 1 under a log scale),
    // then a jump there.
    const double before = std::nextafter(y, -inf);
    if (before > f.x(n - 1)) out.push(before, f.at(before));
    if (std::isfinite(y)) out.jump(beyond);
  }
}

}  // namespace

const char* convention_name(OpacityConvention c) {
  switch (c) {
    case OpacityConvention::density: return "density";
    case OpacityConvention::unit_distance: return "unit_distance";
    case OpacityConvention::sample_distance: return "sample_distance";
    case OpacityConvention::nerf_sigma: return "nerf_sigma";
  }
  return "?";
}

double density_from_opacity(double y, OpacityConvention convention, double distance) {
  switch (convention) {
    case OpacityConvention::density:
    case OpacityConvention::nerf_sigma:
      return y;
    case OpacityConvention::unit_distance:
      return y / distance;
    case OpacityConvention::sample_distance:
      return -std::log1p(-y) / distance;  // -ln(1 - y)/d without cancellation for small y
  }
  return y;
}

TfImport import_vtk_transfer_function(const VtkColorTransferFunction& color,
                                      const VtkPiecewiseFunction& opacity,
                                      const TfImportOptions& options) {
  if (color.nodes.empty() || opacity.nodes.empty())
    throw std::invalid_argument("a transfer function needs at least one node");
  const OpacityConvention conv = options.convention;
  const double dist = options.distance;
  double max_rho = 0.0;
  for (const VtkPiecewiseNode& p : opacity.nodes) {
    if (conv == OpacityConvention::sample_distance && !(p.y < 1.0))
      throw std::invalid_argument("opacity per sample must be < 1");
    max_rho = std::max(max_rho, density_from_opacity(p.y, conv, dist));
  }
  auto rho = [conv, dist](double y) { return density_from_opacity(y, conv, dist); };

  TfImport out;
  {
    const auto& nodes = opacity.nodes;
    Intervals f;
    f.count_nodes = nodes.size();
    f.x = [&](std::size_t k) { return nodes[k].x; };
    f.shape = [&](std::size_t k) { return piecewise_interval_shape(nodes[k]); };
    f.midpoint = [&](std::size_t k) { return nodes[k].midpoint; };
    f.step = [&](std::size_t k) { return step_location(nodes[k].x, nodes[k + 1].x, nodes[k].midpoint); };
    f.value = [&](std::size_t k, double x) { return Values{rho(opacity.interval_value(k, x)), 0, 0}; };
    f.left_value = [&](std::size_t k) { return Values{rho(nodes[k].y), 0, 0}; };
    f.right_value = [&](std::size_t k) { return Values{rho(nodes[k + 1].y), 0, 0}; };
    f.at = [&](double x) { return Values{rho(opacity(x)), 0, 0}; };
    f.linear_map = conv != OpacityConvention::sample_distance;
    Builder b(1, options.tolerance * (max_rho > 0.0 ? max_rho : 1.0));
    linearise(f, b);
    out.density = b.finish(out.transfer.density);
  }
  {
    const auto& nodes = color.nodes;
    Intervals f;
    f.count_nodes = nodes.size();
    f.x = [&](std::size_t k) { return nodes[k].x; };
    f.shape = [&](std::size_t k) { return color.interval_shape(k); };
    f.midpoint = [&](std::size_t k) { return nodes[k].midpoint; };
    f.step = [&](std::size_t k) { return color.step_location(k); };
    f.value = [&](std::size_t k, double x) { return color.interval_value(k, x); };
    f.left_value = [&](std::size_t k) { return nodes[k].rgb; };
    f.right_value = [&](std::size_t k) { return nodes[k + 1].rgb; };
    f.at = [&](double x) { return color(x); };
    Builder b(3, options.tolerance);
    linearise(f, b);
    out.color = b.finish(out.transfer.color);
  }
  return out;
}

}  // namespace rayint
