// Gauss-Legendre nodes and weights on [0, 1]; see gauss_legendre.hpp.
#include "rayint/special/gauss_legendre.hpp"

#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"

namespace rayint {

namespace {

// P_n(x) by the three-term recurrence, and P_n'(x) = n (x P_n - P_{n-1}) / (x^2 - 1).
struct LegendreValue {
  double p, dp;
};
LegendreValue legendre(int n, double x) {
  double p0 = 1, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  if (n == 1) p0 = 1;
  return {p1, n * (x * p1 - p0) / (x * x - 1)};
}

}  // namespace

GaussLegendre gauss_legendre_01(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre_01: n must be >= 1");
  GaussLegendre q;
  q.nodes.resize(static_cast<std::size_t>(n));
  q.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Root i of P_n on [-1, 1] in descending order; Tricomi's guess.
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      const LegendreValue v = legendre(n, x);
      const double dx = v.p / v.dp;
      x -= dx;
      if (std::fabs(dx) < 1e-15) break;
    }
    const double dp = legendre(n, x).dp;  // derivative at the converged root
    const double w = 2 / ((1 - x * x) * dp * dp);
    // map [-1, 1] -> [0, 1], ascending
    const std::size_t j = static_cast<std::size_t>(n - 1 - i);
    q.nodes[j] = 0.5 * (x + 1);
    q.weights[j] = 0.5 * w;
  }
  return q;
}

}  // namespace rayint
