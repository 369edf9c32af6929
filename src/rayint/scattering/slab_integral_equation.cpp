// The integral equation for the source function of an isotropic slab; see slab_integral_equation.hpp.
#include "rayint/scattering/slab_integral_equation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/special_functions/expint.hpp>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"

namespace rayint {

namespace {
// E_n(x), x >= 0, n >= 2 (E_n(0) = 1/(n-1)); underflows to 0 beyond x ~ 700.
double En(int n, double x) {
  if (x <= 0) return 1.0 / (n - 1);
  if (x > 700) return 0.0;
  return boost::math::expint(n, x);
}

// Weights of the two hat functions of a segment against the kernel E_n(u), u the distance from
// the evaluation point, over u in [ua, ub] (ua < ub, h = ub - ua): the node at distance ua gets
// int (ub - u)/h E_n, the node at ub gets int (u - ua)/h E_n. With E_n' = -E_{n-1}:
//   int (ub - u) E_n du = h E_{n+1}(ua) - (E_{n+2}(ua) - E_{n+2}(ub)),
//   int (u - ua) E_n du = (E_{n+2}(ua) - E_{n+2}(ub)) - h E_{n+1}(ub).
struct HatWeights {
  double near, far;
};
HatWeights hat_weights(const double* E1n, const double* E2n, std::size_t a, std::size_t b, double h) {
  // E1n[i] = E_{n+1}(u_i), E2n[i] = E_{n+2}(u_i) at the two ends a (near), b (far).
  const double d = E2n[a] - E2n[b];
  return {(h * E1n[a] - d) / h, (d - h * E1n[b]) / h};
}

// Same for the kernel e^{-u/mu}/mu on [ua, ub]: with x = h/mu,
//   int (ub - u)/h e^{-u/mu}/mu du = e^{-ua/mu} (1 - (1 - e^{-x})/x),
//   int (u - ua)/h e^{-u/mu}/mu du = e^{-ua/mu} ((1 - e^{-x})/x - e^{-x}).
HatWeights exp_hat_weights(double ua, double h, double mu) {
  const double x = h / mu, scale = std::exp(-ua / mu);
  double g;  // (1 - e^{-x})/x
  double near;  // 1 - g
  double far;   // g - e^{-x}
  if (x < 1e-3) {  // Taylor, truncation error < x^4/120 < 1e-14
    g = 1 - x / 2 + x * x / 6 - x * x * x / 24;
    near = x / 2 - x * x / 6 + x * x * x / 24;
    far = x / 2 - x * x / 3 + x * x * x / 8;
  } else {
    g = step_weight(x);
    near = 1 - g;
    far = g - std::exp(-x);
  }
  return {scale * near, scale * far};
}

std::vector<double> graded_mesh(double tau, int segments, double q) {
  std::vector<double> t(static_cast<std::size_t>(segments) + 1);
  for (int i = 0; i <= segments; ++i) {
    const double s = static_cast<double>(i) / segments;
    const double a = std::pow(s, q), b = std::pow(1 - s, q);
    t[static_cast<std::size_t>(i)] = tau * a / (a + b);
  }
  t.front() = 0;
  t.back() = tau;
  return t;
}

// Integral of the piecewise-linear S against E_n(|t0 - t|) over the slab, t0 = t[k0] a node.
double kernel_integral(const std::vector<double>& t, const std::vector<double>& S, std::size_t k0, int n) {
  const std::size_t N = t.size();
  std::vector<double> A(N), B(N);
  for (std::size_t i = 0; i < N; ++i) {
    const double u = std::fabs(t[i] - t[k0]);
    A[i] = En(n + 1, u);
    B[i] = En(n + 2, u);
  }
  double sum = 0;
  for (std::size_t m = 0; m + 1 < N; ++m) {
    const double h = t[m + 1] - t[m];
    const bool right = m >= k0;  // segment beyond the evaluation point: near end is m
    const std::size_t a = right ? m : m + 1, b = right ? m + 1 : m;
    const HatWeights w = hat_weights(A.data(), B.data(), a, b, h);
    sum += w.near * S[a] + w.far * S[b];
  }
  return sum;
}

double exp_integral(const std::vector<double>& t, const std::vector<double>& S, double mu, bool from_top) {
  const std::size_t N = t.size();
  const double tau = t.back();
  double sum = 0;
  for (std::size_t m = 0; m + 1 < N; ++m) {
    const double h = t[m + 1] - t[m];
    const std::size_t a = from_top ? m : m + 1, b = from_top ? m + 1 : m;
    const double ua = from_top ? t[m] : tau - t[m + 1];
    const HatWeights w = exp_hat_weights(ua, h, mu);
    sum += w.near * S[a] + w.far * S[b];
  }
  return sum;
}

void check(const SlabProblem& p) {
  validate(p);
  if (p.phase.kind() != PhaseFunction::Kind::isotropic)
    throw std::invalid_argument("slab integral equation: isotropic scattering only (phase function is " +
                                std::string(p.phase.name()) + ")");
}
}  // namespace

SlabSourceFunction slab_source_function(const SlabProblem& p, int segments, double grading) {
  check(p);
  if (segments < 2) throw std::invalid_argument("slab integral equation: segments must be >= 2");
  if (!(grading >= 1)) throw std::invalid_argument("slab integral equation: grading must be >= 1");
  SlabSourceFunction f;
  f.t = graded_mesh(p.tau, segments, grading);
  const std::vector<double>& t = f.t;
  const std::size_t N = t.size();
  const double omega = p.albedo;
  // E2, E3 of all node distances (E1 kernel: E_{n+1} = E2, E_{n+2} = E3).
  Eigen::MatrixXd E2(N, N), E3(N, N);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i; j < N; ++j) {
      const double u = t[j] - t[i];
      E2(i, j) = E2(j, i) = En(2, u);
      E3(i, j) = E3(j, i) = En(3, u);
    }
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(N, N);
  Eigen::VectorXd rhs(N);
  for (std::size_t k = 0; k < N; ++k) {
    for (std::size_t m = 0; m + 1 < N; ++m) {
      const double h = t[m + 1] - t[m];
      const bool right = m >= k;
      const std::size_t a = right ? m : m + 1, b = right ? m + 1 : m;
      const double d = E3(k, a) - E3(k, b);
      const double w_near = (h * E2(k, a) - d) / h, w_far = (d - h * E2(k, b)) / h;
      A(k, a) -= 0.5 * omega * w_near;
      A(k, b) -= 0.5 * omega * w_far;
    }
    rhs(k) = p.source == SlabSource::beam ? omega / (4 * p.mu0) * std::exp(-t[k] / p.mu0)
                                          : 0.5 * omega * En(2, t[k]);
  }
  const Eigen::VectorXd S = A.partialPivLu().solve(rhs);
  f.S.assign(S.data(), S.data() + N);
  return f;
}

SlabValues solve_slab_integral_equation_mesh(const SlabProblem& p, int segments, double grading) {
  const SlabSourceFunction f = slab_source_function(p, segments, grading);
  const std::vector<double>& t = f.t;
  const std::size_t N = t.size();
  const bool iso = p.source == SlabSource::isotropic;
  SlabValues v;
  v.flux_up_top = 2 * kPi * kernel_integral(t, f.S, 0, 2);
  v.diffuse_down_bottom = 2 * kPi * kernel_integral(t, f.S, N - 1, 2) + (iso ? 2 * kPi * En(3, p.tau) : 0.0);
  v.direct_down_bottom = iso ? 0.0 : kPi * std::exp(-p.tau / p.mu0);
  for (double mu : p.mu_up) v.intensity_up_top.push_back(exp_integral(t, f.S, mu, true));
  for (double mu : p.mu_down)
    v.intensity_down_bottom.push_back(exp_integral(t, f.S, mu, false) + (iso ? std::exp(-p.tau / mu) : 0.0));
  return v;
}

namespace {
// Applies op(field of a, field of b, field of c, field of out) to every scalar of SlabValues.
template <class Op>
void for_each_value(const SlabValues& a, const SlabValues& b, const SlabValues& c, SlabValues& out, Op op) {
  out.flux_up_top = op(a.flux_up_top, b.flux_up_top, c.flux_up_top);
  out.diffuse_down_bottom = op(a.diffuse_down_bottom, b.diffuse_down_bottom, c.diffuse_down_bottom);
  out.direct_down_bottom = op(a.direct_down_bottom, b.direct_down_bottom, c.direct_down_bottom);
  out.intensity_up_top.resize(a.intensity_up_top.size());
  for (std::size_t i = 0; i < a.intensity_up_top.size(); ++i)
    out.intensity_up_top[i] = op(a.intensity_up_top[i], b.intensity_up_top[i], c.intensity_up_top[i]);
  out.intensity_down_bottom.resize(a.intensity_down_bottom.size());
  for (std::size_t i = 0; i < a.intensity_down_bottom.size(); ++i)
    out.intensity_down_bottom[i] =
        op(a.intensity_down_bottom[i], b.intensity_down_bottom[i], c.intensity_down_bottom[i]);
}

double observed_order(double q0, double q1, double q2) {
  const double d1 = q1 - q0, d2 = q2 - q1;
  if (d2 == 0 || d1 == 0) return 0;  // exact on every mesh (e.g. the direct beam)
  return std::log2(std::fabs(d1 / d2));
}
}  // namespace

SlabIntegralEquationResult solve_slab_integral_equation(const SlabProblem& p,
                                                        const SlabIntegralEquationOptions& o) {
  if (o.levels < 3) throw std::invalid_argument("slab integral equation: levels must be >= 3");
  const auto start = std::chrono::steady_clock::now();
  SlabIntegralEquationResult r;
  int n = o.segments;
  for (int k = 0; k < o.levels; ++k, n *= 2) {
    r.meshes.push_back(solve_slab_integral_equation_mesh(p, n, o.grading));
    r.finest_segments = n;
  }
  const std::size_t L = r.meshes.size();
  const auto extrapolate = [](double a, double b, double c) {
    const double order = observed_order(a, b, c);
    if (order == 0) return c;
    const double pc = std::clamp(order, 1.0, 4.0);
    return c + (c - b) / (std::pow(2.0, pc) - 1);
  };
  const SlabValues &q0 = r.meshes[L - 3], &q1 = r.meshes[L - 2], &q2 = r.meshes[L - 1];
  for_each_value(q0, q1, q2, r.observed_order, observed_order);
  for_each_value(q0, q1, q2, r.values, extrapolate);
  if (L >= 4) {  // error of the extrapolation: against the one from the three coarser meshes
    SlabValues previous;
    for_each_value(r.meshes[L - 4], q0, q1, previous, extrapolate);
    for_each_value(r.values, previous, previous, r.error_estimate,
                   [](double x, double y, double) { return std::fabs(x - y); });
  } else {
    for_each_value(r.values, q2, q2, r.error_estimate, [](double x, double c, double) { return std::fabs(x - c); });
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rayint
