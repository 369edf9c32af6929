#include "rayint/model/ray_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>

namespace rayint {
namespace {

// v resized to n entries, all zero, as bytes (an all-zero double is +0.0): memset is several
// times faster than assign()'s loop over 24-byte entries (~3% of a long ray's gradient).
template <class T>
void assign_zeros(std::vector<T>& v, std::size_t n) {
  static_assert(std::is_trivially_copyable<T>::value, "zeroed as bytes");
  v.resize(n);
  if (n > 0) std::memset(static_cast<void*>(v.data()), 0, n * sizeof(T));
}

}  // namespace

RayGradient RayGradient::zeros(const TransferFunctions& tf, const Ray& ray) {
  RayGradient g;
  g.reset(tf, ray);
  return g;
}

void RayGradient::reset(const TransferFunctions& tf, const Ray& ray) {
  const std::size_t m = ray.segments.size();
  intensity = background = Rgb{};
  undefined.clear();
  assign_zeros(length, m);
  assign_zeros(scalar_far, m);
  assign_zeros(scalar_exit, m);
  for (int c = 0; c < kChannels; ++c) {
    assign_zeros(density[c], tf.density[c].scalar.size());
    assign_zeros(color[c], tf.color[c].scalar.size());
  }
}

double RayGradient::channel_scale(int c) const {
  double m = 0.0;
  const bool skip_nan = !undefined.empty();
  for_each(c, [&m, skip_nan](double v, const char*, std::size_t, const char*) {
    if (skip_nan && std::isnan(v)) return;
    if (std::isnan(v) || std::fabs(v) > m) m = std::isnan(v) ? v : std::max(m, std::fabs(v));
  });
  return m;
}

bool RayGradient::all_finite() const {
  // Bitwise &, not &&: no branch per entry.
  const auto rgb = [](const Rgb& v) { return std::isfinite(v[0]) & std::isfinite(v[1]) & std::isfinite(v[2]); };
  bool ok = rgb(background);
  for (const auto* block : {&length, &scalar_far, &scalar_exit})
    for (const Rgb& v : *block) ok &= rgb(v);
  for (int c = 0; c < kChannels; ++c)
    for (const auto* nodes : {&density[c], &color[c]})
      for (const NodeDerivative& d : *nodes) ok &= std::isfinite(d.position) & std::isfinite(d.value);
  return ok;
}

NodeWeights node_weights(const PiecewiseLinear& f, double lo, double s) {
  // k: the first node with scalar > lo (scalar[k-1] <= lo < scalar[k]).
  return node_weights_in(
      f, static_cast<std::size_t>(std::upper_bound(f.scalar.begin(), f.scalar.end(), lo) - f.scalar.begin()), s);
}

NodeWeights node_weights_in(const PiecewiseLinear& f, std::size_t k, double s) {
  NodeWeights nw;
  const std::size_t n = f.scalar.size();
  if (k == 0 || k == n) {  // constant extension (or a single node)
    nw.count = 1;
    nw.node[0] = k == 0 ? 0 : n - 1;
    nw.w[0] = 1.0;
    return nw;
  }
  const double p0 = f.scalar[k - 1], p1 = f.scalar[k];
  const double span = p1 - p0;
  const double slope = (f.value[k] - f.value[k - 1]) / span;
  // f(s) = v0 (p1 - s)/span + v1 (s - p0)/span, each distance computed directly.
  const double w0 = (p1 - s) / span, w1 = (s - p0) / span;
  nw.count = 2;
  nw.node[0] = k - 1;
  nw.node[1] = k;
  nw.w[0] = w0;
  nw.w[1] = w1;
  nw.slope = slope;
  nw.dp[0] = -slope * w0;  // d/dp0 of v0 + (s - p0) slope
  nw.dp[1] = -slope * w1;  // d/dp1 of v1 - (p1 - s) slope
  return nw;
}

std::size_t jump_node(const PiecewiseLinear& f, double x) {
  const auto it = std::lower_bound(f.scalar.begin(), f.scalar.end(), x);
  if (it == f.scalar.end() || *it != x || it + 1 == f.scalar.end() || *(it + 1) != x) return kNoJump;
  return static_cast<std::size_t>(it - f.scalar.begin());
}

void tie_jump_positions(const TransferFunctions& tf, std::array<std::vector<NodeDerivative>, kChannels>& density,
                        std::array<std::vector<NodeDerivative>, kChannels>& color) {
  for (int c = 0; c < kChannels; ++c)
    for (const auto& [f, nodes] : {std::pair{&tf.density[c], &density[c]}, std::pair{&tf.color[c], &color[c]}})
      for (std::size_t i = 0; i + 1 < f->scalar.size(); ++i)
        if (f->scalar[i] == f->scalar[i + 1]) {
          (*nodes)[i].position += (*nodes)[i + 1].position;
          (*nodes)[i + 1].position = 0.0;
        }
}

}  // namespace rayint
