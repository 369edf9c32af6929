// The P_N (spherical-harmonics) method for the plane-parallel slab; see pn.hpp.
#include "rayint/scattering/pn.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/core/math.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/special/gauss_legendre.hpp"

namespace rayint {

namespace {
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;
using Index = Eigen::Index;

// P_0(x) .. P_L(x) by Bonnet's recurrence.
std::vector<double> legendre_all(double x, int L) {
  std::vector<double> P(static_cast<std::size_t>(L) + 1);
  P[0] = 1;
  if (L >= 1) P[1] = x;
  for (int l = 1; l < L; ++l)
    P[static_cast<std::size_t>(l) + 1] =
        ((2 * l + 1) * x * P[static_cast<std::size_t>(l)] - l * P[static_cast<std::size_t>(l) - 1]) / (l + 1);
  return P;
}

// (1 - e^{-x}(1 + x)) / x^2 for x >= 0 (1/2 at 0): int_0^T t e^{-s t} dt = T^2 phi2(s T).
// Below x = 0.5 the Maclaurin series sum_n (-x)^n (n+1)/(n+2)! (the closed form cancels there,
// losing about eps/x^2); its terms fall by x/n, so 24 terms leave < 1e-30. Above 0.5 the
// closed form's cancellation costs at most a factor 1/0.09 of eps.
double phi2(double x) {
  if (x < 0.5) {
    double term = 0.5, sum = 0.5;  // n = 0: 1/2!
    for (int n = 1; n < 24; ++n) {
      term *= -x / (n + 2);  // (-x)^n / (n+2)!
      sum += term * (n + 1);
    }
    return sum;
  }
  return (1 - std::exp(-x) * (1 + x)) / (x * x);
}

// int_0^T e^{-r1 s - r2 (T - s)} ds for rates r1, r2 >= 0, every exponential <= 1.
double two_rate(double r1, double r2, double T) {
  return std::exp(-std::min(r1, r2) * T) * attenuated_length(std::fabs(r1 - r2), T);
}

// One term of the solution: a shape function of depth times a vector of moments a_0..a_N.
enum class Shape { from_top, from_bottom, ramp };  // e^{-r t}, e^{-r (tau - t)}, t / tau
struct Term {
  Shape shape;
  double rate;
  Vector a;
};
using Column = std::vector<Term>;

double shape_at(const Term& term, double t, double tau) {
  switch (term.shape) {
    case Shape::from_top: return std::exp(-term.rate * t);
    case Shape::from_bottom: return std::exp(-term.rate * (tau - t));
    case Shape::ramp: return t / tau;
  }
  return 0;
}

// int_0^tau g(t) e^{-t/mu} dt/mu: the term's shape g seen from the top in direction -mu.
double up_integral(Shape shape, double rate, double tau, double mu) {
  const double s = 1 / mu;
  switch (shape) {
    case Shape::from_top: return s * attenuated_length(rate + s, tau);
    case Shape::from_bottom: return s * two_rate(s, rate, tau);
    case Shape::ramp: return tau * s * phi2(tau * s);
  }
  return 0;
}

// int_0^tau g(t) e^{-(tau - t)/mu} dt/mu: seen from the bottom in direction +mu.
double down_integral(Shape shape, double rate, double tau, double mu) {
  const double s = 1 / mu;
  switch (shape) {
    case Shape::from_top: return s * two_rate(rate, s, tau);
    case Shape::from_bottom: return s * attenuated_length(rate + s, tau);
    case Shape::ramp: {
      const double x = tau * s;
      return x * (step_weight(x) - phi2(x));
    }
  }
  return 0;
}

struct Setup {
  int N = 0;
  std::vector<double> chi;        // chi_0..chi_N for the moment equations
  std::vector<double> chi_table;  // whole table (empty: use the PhaseFunction exactly)
};

// The exact azimuthally averaged phase function for the single-scattering term.
double exact_p0(const SlabProblem& p, const Setup& s, double mu_a, double mu_b) {
  if (s.chi_table.empty()) return azimuthal_phase(p.phase, mu_a, mu_b);
  const int L = static_cast<int>(s.chi_table.size()) - 1;
  const std::vector<double> Pa = legendre_all(mu_a, L), Pb = legendre_all(mu_b, L);
  double sum = 0;
  for (int l = 0; l <= L; ++l) {
    const auto u = static_cast<std::size_t>(l);
    sum += (2 * l + 1) * s.chi_table[u] * Pa[u] * Pb[u];
  }
  return sum / (4 * kPi);
}

PnSolution solve_core(const SlabProblem& p, const Setup& s, PnBoundary boundary, double mu0) {
  const int N = s.N, M = (N + 1) / 2;
  const double omega = p.albedo, tau = p.tau;
  const bool beam = p.source == SlabSource::beam;
  auto b = [&](int l) { return 1 - omega * s.chi[static_cast<std::size_t>(l)]; };

  // A of Eq. (1) and its even/odd blocks C (even rows, odd columns) and D (odd rows, even columns).
  Matrix A = Matrix::Zero(N + 1, N + 1);
  for (int k = 0; k <= N; ++k) {
    if (k >= 1) A(k, k - 1) = static_cast<double>(k) / (2 * k - 1);
    if (k + 1 <= N) A(k, k + 1) = static_cast<double>(k + 1) / (2 * k + 3);
  }
  Matrix C(M, M), D(M, M);
  for (int i = 0; i < M; ++i)
    for (int m = 0; m < M; ++m) {
      C(i, m) = A(2 * i, 2 * m + 1);
      D(m, i) = A(2 * m + 1, 2 * i);
    }
  Vector bo_inv(M), we(M), be(M);
  for (int m = 0; m < M; ++m) {
    bo_inv(m) = 1 / b(2 * m + 1);
    we(m) = 1.0 / (4 * m + 1);  // 1/(2l+1) for l = 2m: makes W A symmetric
    be(m) = b(2 * m);
  }
  // Eq. (2), symmetric-definite: (W_e B_e) u = kappa^2 (W_e C B_o^{-1} D) u.
  Matrix S1 = we.asDiagonal() * C * bo_inv.asDiagonal() * D;
  S1 = 0.5 * (S1 + S1.transpose()).eval();
  const Matrix S2 = Matrix((we.array() * be.array()).matrix().asDiagonal());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> es(S2, S1);
  if (es.info() != Eigen::Success) throw std::runtime_error("pn: the eigen-decomposition failed");
  Vector lambda = es.eigenvalues();
  Matrix U = es.eigenvectors();
  const bool conservative = be(0) == 0;  // omega chi_0 = 1: kappa = 0 is exact, u = e_0
  if (conservative) {
    lambda(0) = 0;
    U.col(0) = Vector::Unit(M, 0);
  }

  PnSolution sol;
  PnDiagnostics& dg = sol.diagnostics;
  dg.order = N;
  dg.modes = M;
  dg.conservative = conservative;
  dg.kappa_min = std::sqrt(std::max(0.0, lambda(0)));
  dg.kappa_max = std::sqrt(std::max(0.0, lambda(M - 1)));
  for (int j = 0; j < M; ++j)
    if (lambda(j) > 0) dg.resonance_gap = std::min(dg.resonance_gap, std::fabs(std::sqrt(lambda(j)) * mu0 - 1));

  auto assemble = [&](const Vector& even, const Vector& odd) {
    Vector a(N + 1);
    for (int m = 0; m < M; ++m) {
      a(2 * m) = even(m);
      a(2 * m + 1) = odd(m);
    }
    return a;
  };
  std::vector<Column> columns;
  for (int j = 0; j < M; ++j) {
    Vector u = U.col(j);
    u /= u.cwiseAbs().maxCoeff();
    const Vector z = bo_inv.asDiagonal() * (D * u);
    if (conservative && j == 0) {
      columns.push_back({Term{Shape::from_top, 0.0, assemble(u, Vector::Zero(M))}});
      columns.push_back({Term{Shape::ramp, 0.0, assemble(u, Vector::Zero(M))},
                         Term{Shape::from_top, 0.0, assemble(Vector::Zero(M), -z / tau)}});
      continue;
    }
    const double kappa = std::sqrt(std::max(0.0, lambda(j)));
    columns.push_back({Term{Shape::from_top, kappa, assemble(u, kappa * z)}});
    columns.push_back({Term{Shape::from_bottom, kappa, assemble(u, -kappa * z)}});
  }

  // Particular solution of the beam.
  Vector part = Vector::Zero(N + 1);
  if (beam) {
    const std::vector<double> P0 = legendre_all(mu0, N);
    Vector q(N + 1);
    for (int k = 0; k <= N; ++k)
      q(k) = omega * (2 * k + 1) * s.chi[static_cast<std::size_t>(k)] * P0[static_cast<std::size_t>(k)] / (4 * mu0);
    Matrix Bm = Matrix::Zero(N + 1, N + 1);
    for (int k = 0; k <= N; ++k) Bm(k, k) = b(k);
    part = (Bm - A / mu0).partialPivLu().solve(q);
  }

  // Boundary rows.
  Matrix Rtop(M, N + 1), Rbot(M, N + 1);
  Vector gtop = Vector::Zero(M);
  const bool iso = !beam;
  // h_l = int_0^1 mu P_l(mu) dmu: the downward flux at the bottom is 2 pi sum_l h_l a_l(tau).
  Vector h = Vector::Zero(N + 1);
  {
    const GaussLegendre gl = gauss_legendre_01(N + 1);
    for (std::size_t q = 0; q < gl.nodes.size(); ++q) {
      const std::vector<double> P = legendre_all(gl.nodes[q], N);
      for (int l = 0; l <= N; ++l) h(l) += gl.weights[q] * gl.nodes[q] * P[static_cast<std::size_t>(l)];
    }
  }
  // Lambertian ground (pn.hpp): the upward intensity at the bottom is the constant
  // I_g = (A / pi) F_down = 2 A h . a(tau) + A e^{-tau/mu0} (beam). Per boundary row, its weight
  // against that constant: int_0^1 P_i dmu (Marshak) or 1 (Mark).
  const double ground = p.ground_albedo;
  Vector gbot = Vector::Zero(M);
  if (boundary == PnBoundary::marshak) {
    const GaussLegendre gl = gauss_legendre_01(N + 1);  // exact for degree <= 2N + 1
    Rtop.setZero();
    for (std::size_t q = 0; q < gl.nodes.size(); ++q) {
      const std::vector<double> P = legendre_all(gl.nodes[q], N);
      for (int m = 0; m < M; ++m) {
        const double wp = gl.weights[q] * P[static_cast<std::size_t>(2 * m + 1)];
        for (int l = 0; l <= N; ++l) Rtop(m, l) += wp * P[static_cast<std::size_t>(l)];
        gbot(m) += wp;
      }
    }
    for (int l = 0; l <= N; ++l) Rbot.col(l) = (l % 2 ? -1.0 : 1.0) * Rtop.col(l);
    if (iso) gtop = gbot;
  } else {
    const GaussLegendre gl = gauss_legendre_01(N + 1);  // roots of P_{N+1} mapped to [0, 1]
    int m = 0;
    for (double x : gl.nodes) {
      const double mu = 2 * x - 1;
      if (mu <= 0) continue;
      const std::vector<double> P = legendre_all(mu, N);
      for (int l = 0; l <= N; ++l) {
        Rtop(m, l) = P[static_cast<std::size_t>(l)];
        Rbot(m, l) = (l % 2 ? -1.0 : 1.0) * P[static_cast<std::size_t>(l)];
      }
      if (iso) gtop(m) = 1;
      gbot(m) = 1;
      ++m;
    }
  }

  Rbot -= 2 * ground * gbot * h.transpose();

  const Index n = 2 * M;
  Matrix S(n, n);
  for (Index c = 0; c < n; ++c) {
    Vector a0 = Vector::Zero(N + 1), a1 = Vector::Zero(N + 1);
    for (const Term& t : columns[static_cast<std::size_t>(c)]) {
      a0 += shape_at(t, 0, tau) * t.a;
      a1 += shape_at(t, tau, tau) * t.a;
    }
    S.col(c) << Rtop * a0, Rbot * a1;
  }
  Vector rhs(n);
  const double beam_bottom = beam ? std::exp(-tau / mu0) : 0.0;
  rhs << gtop - Rtop * part, ground * beam_bottom * gbot - Rbot * (part * beam_bottom);
  const Eigen::PartialPivLU<Matrix> lu(S);
  dg.rcond = lu.rcond();
  const Vector coef = lu.solve(rhs);

  std::vector<Term> terms;
  for (Index c = 0; c < n; ++c)
    for (const Term& t : columns[static_cast<std::size_t>(c)])
      terms.push_back(Term{t.shape, t.rate, coef(c) * t.a});
  if (beam) terms.push_back(Term{Shape::from_top, 1 / mu0, part});

  Vector atop = Vector::Zero(N + 1), abot = Vector::Zero(N + 1);
  for (const Term& t : terms) {
    atop += shape_at(t, 0, tau) * t.a;
    abot += shape_at(t, tau, tau) * t.a;
  }
  // Fluxes from the moments.
  {
    double up = 0, down = 0;
    for (int l = 0; l <= N; ++l) {
      up += (l % 2 ? -1.0 : 1.0) * h(l) * atop(l);
      down += h(l) * abot(l);
    }
    sol.values.flux_up_top = 2 * kPi * up;
    sol.values.diffuse_down_bottom = 2 * kPi * down;
    sol.values.direct_down_bottom = beam ? kPi * std::exp(-tau / p.mu0) : 0.0;
  }
  // The ground's radiance (from the moments' downward flux), seen from the top through e^{-tau/mu}.
  const double ground_radiance = ground * (2 * h.dot(abot) + beam_bottom);

  // Source-function integration (pn.hpp). Amplitude of a term's source toward cosine mu (signed).
  auto amplitude = [&](const Term& t, const std::vector<double>& P) {
    double sum = 0;
    for (int l = 0; l <= N; ++l)
      sum += s.chi[static_cast<std::size_t>(l)] * t.a(l) * P[static_cast<std::size_t>(l)];
    return omega * sum;
  };
  const double F0 = kPi / mu0;
  for (double mu : p.mu_up) {
    const std::vector<double> P = legendre_all(-mu, N);
    double I = ground_radiance * std::exp(-tau / mu);
    for (const Term& t : terms) I += amplitude(t, P) * up_integral(t.shape, t.rate, tau, mu);
    if (beam)
      I += omega * F0 * exact_p0(p, s, -mu, mu0) * up_integral(Shape::from_top, 1 / mu0, tau, mu);
    sol.values.intensity_up_top.push_back(I);
    double series = 0;
    for (int l = 0; l <= N; ++l) series += atop(l) * P[static_cast<std::size_t>(l)];
    sol.series_up_top.push_back(series);
  }
  for (double mu : p.mu_down) {
    const std::vector<double> P = legendre_all(mu, N);
    double I = iso ? std::exp(-tau / mu) : 0.0;
    for (const Term& t : terms) I += amplitude(t, P) * down_integral(t.shape, t.rate, tau, mu);
    if (beam)
      I += omega * F0 * exact_p0(p, s, mu, mu0) * down_integral(Shape::from_top, 1 / mu0, tau, mu);
    sol.values.intensity_down_bottom.push_back(I);
    double series = 0;
    for (int l = 0; l <= N; ++l) series += abot(l) * P[static_cast<std::size_t>(l)];
    sol.series_down_bottom.push_back(series);
  }
  return sol;
}

bool all_finite(const PnSolution& s) {
  const SlabValues& v = s.values;
  bool ok = std::isfinite(v.flux_up_top) && std::isfinite(v.diffuse_down_bottom) &&
            std::isfinite(v.direct_down_bottom);
  for (const auto* list : {&v.intensity_up_top, &v.intensity_down_bottom, &s.series_up_top,
                           &s.series_down_bottom})
    for (double x : *list) ok = ok && std::isfinite(x);
  return ok;
}

}  // namespace

std::vector<double> phase_legendre_coefficients(const PhaseFunction& phase, int lmax) {
  if (lmax < 0) throw std::invalid_argument("pn: lmax must be >= 0");
  std::vector<double> chi(static_cast<std::size_t>(lmax) + 1, 0.0);
  chi[0] = 1;
  switch (phase.kind()) {
    case PhaseFunction::Kind::isotropic:
      return chi;
    case PhaseFunction::Kind::henyey_greenstein:
      for (int l = 1; l <= lmax; ++l) chi[static_cast<std::size_t>(l)] = std::pow(phase.g(), l);
      return chi;
    case PhaseFunction::Kind::lambert_sphere: {
      // chi_l = 2 pi int_{-1}^{1} p(x) P_l(x) dx; 2048 points (accuracy in pn.hpp).
      const GaussLegendre gl = gauss_legendre_01(2048);
      std::fill(chi.begin(), chi.end(), 0.0);
      for (std::size_t q = 0; q < gl.nodes.size(); ++q) {
        const double x = 2 * gl.nodes[q] - 1;
        const std::vector<double> P = legendre_all(x, lmax);
        const double w = 4 * kPi * gl.weights[q] * phase.eval(x);
        for (int l = 0; l <= lmax; ++l) chi[static_cast<std::size_t>(l)] += w * P[static_cast<std::size_t>(l)];
      }
      return chi;
    }
  }
  return chi;
}

std::vector<double> legendre_from_table(const std::vector<double>& x, const std::vector<double>& y, int lmax) {
  if (lmax < 0) throw std::invalid_argument("pn: lmax must be >= 0");
  if (x.size() < 2 || x.size() != y.size())
    throw std::invalid_argument("phase table: needs at least two points and as many values as cosines");
  if (x.front() != -1 || x.back() != 1) throw std::invalid_argument("phase table: cosines must run from -1 to 1");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i > 0 && !(x[i] > x[i - 1])) throw std::invalid_argument("phase table: cosines must increase");
    if (!(std::isfinite(y[i]) && y[i] >= 0)) throw std::invalid_argument("phase table: values must be finite and >= 0");
  }
  const GaussLegendre gl = gauss_legendre_01((lmax + 3) / 2 + 1);
  std::vector<double> chi(static_cast<std::size_t>(lmax) + 1, 0.0);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double w = x[i + 1] - x[i];
    for (std::size_t q = 0; q < gl.nodes.size(); ++q) {
      const double u = gl.nodes[q], c = x[i] + u * w;
      const double pv = y[i] + u * (y[i + 1] - y[i]);
      const std::vector<double> P = legendre_all(c, lmax);
      for (int l = 0; l <= lmax; ++l)
        chi[static_cast<std::size_t>(l)] += 2 * kPi * w * gl.weights[q] * pv * P[static_cast<std::size_t>(l)];
    }
  }
  const double norm = chi[0];
  if (!(norm > 0)) throw std::invalid_argument("phase table: its integral is 0");
  for (double& c : chi) c /= norm;
  chi[0] = 1;
  return chi;
}

PnSolution solve_slab_pn(const SlabProblem& p, const PnOptions& o) {
  validate(p);
  const int N = o.order;
  if (N < 1 || N > kPnMaxOrder || N % 2 == 0)
    throw std::invalid_argument("pn: order must be odd and in [1, " + std::to_string(kPnMaxOrder) +
                                "], got " + std::to_string(N));
  Setup s;
  s.N = N;
  if (!o.legendre.empty()) {
    if (o.legendre[0] != 1) throw std::invalid_argument("pn: legendre[0] must be 1 (normalisation)");
    for (std::size_t l = 1; l < o.legendre.size(); ++l)
      if (!(std::fabs(o.legendre[l]) < 1))
        throw std::invalid_argument("pn: legendre[" + std::to_string(l) + "] must be finite with |chi| < 1");
    s.chi_table = o.legendre;
    s.chi.assign(static_cast<std::size_t>(N) + 1, 0.0);
    for (std::size_t l = 0; l < s.chi.size() && l < o.legendre.size(); ++l) s.chi[l] = o.legendre[l];
  } else {
    s.chi = phase_legendre_coefficients(p.phase, N);
  }

  PnSolution sol = solve_core(p, s, o.boundary, p.mu0);
  if (p.source == SlabSource::beam && sol.diagnostics.resonance_gap < kPnResonanceGap) {
    // Resonance 1/mu0 = kappa_j (pn.hpp): the average of the solves at mu0 (1 +- 1e-4).
    const double shift = 1e-4;
    const PnSolution hi = solve_core(p, s, o.boundary, p.mu0 * (1 + shift));
    const PnSolution lo = solve_core(p, s, o.boundary, p.mu0 * (1 - shift));
    auto mean = [](std::vector<double>& out, const std::vector<double>& x, const std::vector<double>& y) {
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = 0.5 * (x[i] + y[i]);
    };
    sol.values.flux_up_top = 0.5 * (hi.values.flux_up_top + lo.values.flux_up_top);
    sol.values.diffuse_down_bottom = 0.5 * (hi.values.diffuse_down_bottom + lo.values.diffuse_down_bottom);
    mean(sol.values.intensity_up_top, hi.values.intensity_up_top, lo.values.intensity_up_top);
    mean(sol.values.intensity_down_bottom, hi.values.intensity_down_bottom, lo.values.intensity_down_bottom);
    mean(sol.series_up_top, hi.series_up_top, lo.series_up_top);
    mean(sol.series_down_bottom, hi.series_down_bottom, lo.series_down_bottom);
    sol.diagnostics.resonance_averaged = true;
    sol.diagnostics.rcond = std::min(hi.diagnostics.rcond, lo.diagnostics.rcond);
  }
  if (!all_finite(sol)) throw std::runtime_error("pn: the solve produced a non-finite value");
  return sol;
}

}  // namespace rayint
