#include "rayint/model/ray_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rayint {

RayGradient RayGradient::zeros(const TransferFunctions& tf, const Ray& ray) {
  RayGradient g;
  g.reset(tf, ray);
  return g;
}

void RayGradient::reset(const TransferFunctions& tf, const Ray& ray) {
  // A jump's two nodes share one scalar: the derivative with respect to its position is a Dirac
  // term the piece chain does not carry, and the pieces' end values would be credited to one node.
  if (tf.has_jump())
    throw std::invalid_argument(
        "gradient: a transfer function with a jump (a scalar repeated) is not differentiated");
  const std::size_t m = ray.segments.size();
  intensity = background = Rgb{};
  length.assign(m, Rgb{});
  scalar_far.assign(m, Rgb{});
  scalar_exit.assign(m, Rgb{});
  for (int c = 0; c < kChannels; ++c) {
    density[c].assign(tf.density[c].scalar.size(), NodeDerivative{});
    color[c].assign(tf.color[c].scalar.size(), NodeDerivative{});
  }
}

double RayGradient::channel_scale(int c) const {
  double m = 0.0;
  for_each(c, [&m](double v, const char*, std::size_t, const char*) {
    if (std::isnan(v) || std::fabs(v) > m) m = std::isnan(v) ? v : std::max(m, std::fabs(v));
  });
  return m;
}

NodeWeights node_weights(const PiecewiseLinear& f, double lo, double s) {
  NodeWeights nw;
  const std::size_t n = f.scalar.size();
  // k: the first node with scalar > lo (scalar[k-1] <= lo < scalar[k]).
  const auto k = static_cast<std::size_t>(std::upper_bound(f.scalar.begin(), f.scalar.end(), lo) -
                                          f.scalar.begin());
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

}  // namespace rayint
