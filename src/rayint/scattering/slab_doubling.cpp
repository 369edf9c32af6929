// Adding-doubling solution of the plane-parallel slab; see slab_doubling.hpp.
#include "rayint/scattering/slab_doubling.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/special_functions/expint.hpp>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/special/gauss_legendre.hpp"

namespace rayint {

namespace {
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// int_0^t exp(-s/a - (t - s)/b) ds for cosines a, b (symmetric in a, b).
double path_integral(double t, double a, double b) {
  const double d = std::fabs(1 / a - 1 / b);
  const double m = std::max(a, b);
  return d == 0 ? t * std::exp(-t / a) : std::exp(-t / m) * -std::expm1(-d * t) / d;
}

struct Responses {
  Vector up, down;  // diffuse response to the source at every direction
};

// The single-scattering layer of thickness t0, doubled k times (thickness t0 2^k).
Responses doubled(const SlabProblem& p, const std::vector<double>& mu, const std::vector<double>& c,
                  double t0, int k) {
  const Eigen::Index n = static_cast<Eigen::Index>(mu.size());
  const bool beam = p.source == SlabSource::beam;
  const double omega = p.albedo;
  Matrix R(n, n), Td(n, n);
  Vector E(n), r = Vector::Zero(n), t = Vector::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double mi = mu[static_cast<std::size_t>(i)];
    E(i) = std::exp(-t0 / mi);
    for (Eigen::Index j = 0; j < n; ++j) {
      const double mj = mu[static_cast<std::size_t>(j)], cj = c[static_cast<std::size_t>(j)];
      R(i, j) = omega * cj * azimuthal_phase(p.phase, mi, -mj) * mj / (mi + mj) *
                -std::expm1(-t0 * (1 / mi + 1 / mj));
      Td(i, j) = omega * cj * azimuthal_phase(p.phase, mi, mj) / mi * path_integral(t0, mj, mi);
    }
    if (beam) {
      const double cb = kPi / p.mu0;
      r(i) = omega * cb * azimuthal_phase(p.phase, mi, -p.mu0) * p.mu0 / (mi + p.mu0) *
             -std::expm1(-t0 * (1 / mi + 1 / p.mu0));
      t(i) = omega * cb * azimuthal_phase(p.phase, mi, p.mu0) / mi * path_integral(t0, p.mu0, mi);
    }
  }
  double e = beam ? std::exp(-t0 / p.mu0) : 0.0;

  const Matrix I = Matrix::Identity(n, n);
  for (int step = 0; step < k; ++step) {
    const Matrix RR = R * R;
    const Eigen::PartialPivLU<Matrix> lu(I - RR);
    const Matrix S = lu.solve(RR);
    const Matrix Tf = Td + Matrix(E.asDiagonal());  // E + Td
    const Matrix Y = Td + S * Tf;
    const Matrix EY = Y + Matrix(E.asDiagonal());   // E + Y
    Matrix R2 = R + Tf * R * EY;
    Matrix Td2 = E.asDiagonal() * Y + Td * EY;
    if (beam) {
      const Vector D = lu.solve(t + e * (R * r));
      const Vector U = e * r + R * D;
      const Vector r2 = r + Tf * U;
      const Vector t2 = e * t + Tf * D;
      r = r2;
      t = t2;
      e = e * e;
    }
    R = std::move(R2);
    Td = std::move(Td2);
    E = E.array().square();
  }
  if (beam) return {r, t};
  // Isotropic incidence of intensity 1: the columns carry the weights, so the row sums are the
  // integrals over the incident hemisphere.
  return {R * Vector::Ones(n), Td * Vector::Ones(n)};
}

}  // namespace

SlabValues solve_slab_doubling(const SlabProblem& p, const DoublingOptions& options,
                               DoublingDiagnostics* diagnostics) {
  validate(p);
  if (p.ground_albedo > 0) {
    // Lambertian ground: the adding of the ground to the black-ground slab (slab.hpp).
    SlabProblem black = p;
    black.ground_albedo = 0;
    SlabProblem iso = black;
    iso.source = SlabSource::isotropic;
    iso.mu_up = p.mu_down;
    iso.mu_down = p.mu_up;
    const SlabValues b = solve_slab_doubling(black, options, diagnostics);
    return add_lambertian_ground(p, b, solve_slab_doubling(iso, options));
  }
  if (options.streams < 2) throw std::invalid_argument("doubling: streams must be >= 2");
  // 1e-3 is a sanity bound on the input (the start must be optically thin), not an accuracy
  // one: at 1e-3 the error is already 1.4e-4 (DISORT 1a) to 0.68 (1e) (slab_doubling.hpp).
  if (!(options.start_thickness > 0 && options.start_thickness <= 1e-3))
    throw std::invalid_argument("doubling: start_thickness must be in (0, 1e-3]");

  // Directions: Gauss cosines (weight 2 pi w) then detector cosines (weight 0).
  const GaussLegendre q = gauss_legendre_01(options.streams);
  std::vector<double> mu = q.nodes, c;
  for (double w : q.weights) c.push_back(2 * kPi * w);
  auto index_of = [&](double m) {
    for (std::size_t i = 0; i < mu.size(); ++i)
      if (mu[i] == m) return i;
    mu.push_back(m);
    c.push_back(0.0);
    return mu.size() - 1;
  };
  std::vector<std::size_t> up_index, down_index;
  for (double m : p.mu_up) up_index.push_back(index_of(m));
  for (double m : p.mu_down) down_index.push_back(index_of(m));
  const bool beam = p.source == SlabSource::beam;

  // Start thickness t0 = tau / 2^k <= start_thickness (and k >= 1 for the extrapolation).
  int k = 0;
  double t0 = p.tau;
  while (t0 > options.start_thickness || k < 1) {
    t0 *= 0.5;
    ++k;
  }
  // Richardson extrapolation in the start thickness: the single-scattering start misses the
  // multiple scattering inside the start layer (double scattering first), an error linear in t0
  // after the doublings, which 2 f(t0) - f(2 t0) removes; the O(t0^2) rest and the rounding that
  // grows as t0 falls are measured in slab_doubling.hpp.
  const Responses fine = doubled(p, mu, c, t0, k);
  Responses res = fine;
  if (options.richardson) {
    const Responses coarse = doubled(p, mu, c, 2 * t0, k - 1);
    res.up = 2 * fine.up - coarse.up;
    res.down = 2 * fine.down - coarse.down;
  }

  SlabValues v;
  for (std::size_t j = 0; j < q.nodes.size(); ++j) {
    const Eigen::Index jj = static_cast<Eigen::Index>(j);
    v.flux_up_top += c[j] * mu[j] * res.up(jj);
    v.diffuse_down_bottom += c[j] * mu[j] * res.down(jj);
  }
  if (beam) {
    v.direct_down_bottom = kPi * std::exp(-p.tau / p.mu0);
  } else {
    v.diffuse_down_bottom += 2 * kPi * boost::math::expint(3, p.tau);
  }
  for (std::size_t i = 0; i < up_index.size(); ++i)
    v.intensity_up_top.push_back(res.up(static_cast<Eigen::Index>(up_index[i])));
  for (std::size_t i = 0; i < down_index.size(); ++i) {
    double value = res.down(static_cast<Eigen::Index>(down_index[i]));
    if (!beam) value += std::exp(-p.tau / p.mu_down[i]);  // unscattered incident intensity
    v.intensity_down_bottom.push_back(value);
  }
  if (diagnostics) {
    diagnostics->doublings = k;
    diagnostics->directions = static_cast<int>(mu.size());
    diagnostics->start_thickness = t0;
  }
  return v;
}

}  // namespace rayint
