// The zonal method for isotropic multiple scattering; see zonal.hpp.
#include "rayint/scattering/zonal.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rayint/scattering/block_runner.hpp"

namespace rayint {

namespace {
constexpr double kPi = 3.14159265358979323846;

double projected_area(const Vec3& h, const Vec3& d) {
  return std::fabs(d[0]) * h[1] * h[2] + std::fabs(d[1]) * h[0] * h[2] + std::fabs(d[2]) * h[0] * h[1];
}

double one_minus_exp_over(double sigma, double s) {
  const double x = sigma * s;
  return x < 1e-8 ? s * (1 - 0.5 * x) : -std::expm1(-x) / sigma;
}
}  // namespace

ZonalSolution solve_zonal(const ScatteringVolume& v, const ZonalOptions& o) {
  v.validate();
  if (v.phase.kind() != PhaseFunction::Kind::isotropic)
    throw std::invalid_argument("zonal method: isotropic scattering only (phase function is " +
                                std::string(v.phase.name()) + ")");
  if (o.grid < 2 || o.grid > 20) throw std::invalid_argument("zonal method: grid must be in [2, 20]");
  const auto start = std::chrono::steady_clock::now();
  ZonalSolution sol;
  sol.cells = make_cell_grid(v, o.grid);
  const CellGrid& g = sol.cells;
  const std::size_t nc = g.size();
  const Vec3 h = g.h;
  const double V = h[0] * h[1] * h[2];
  const double S = 2 * (h[0] * h[1] + h[1] * h[2] + h[0] * h[2]);
  sol.sigma_t.resize(nc);
  std::vector<Vec3> centers(nc);
  for (int k = 0; k < g.n; ++k)
    for (int j = 0; j < g.n; ++j)
      for (int i = 0; i < g.n; ++i) {
        const std::size_t c = g.index(i, j, k);
        centers[c] = g.center(i, j, k);
        sol.sigma_t[c] = v.sigma_t(centers[c]);
      }
  sol.irradiance = first_pass_irradiance(v, g, o.threads);

  // Light power extinguished per cell.
  std::vector<double> P_light(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const double A = projected_area(h, v.light.direction);
    const double sigma = sol.sigma_t[c];
    P_light[c] = sol.irradiance[c] * A * sigma * one_minus_exp_over(sigma, V / A);
  }

  // Form factors F(i, j): fraction of j's isotropic power extinguished in i (row i).
  std::vector<double> F(nc * nc, 0.0);
  const double step = 0.5 * h.minCoeff();
  parallel_for_blocks(nc, o.threads, [&](std::size_t i) {
    const double sigma_i = sol.sigma_t[i];
    for (std::size_t j = 0; j < nc; ++j) {
      if (i == j) {
        F[i * nc + i] = 1 - 1 / (1 + sigma_i * 4 * V / S);
        continue;
      }
      if (sigma_i <= 0) continue;
      const Vec3 diff = centers[i] - centers[j];
      const double r = diff.norm();
      const Vec3 d = diff / r;
      const double A = projected_area(h, d), s_chord = V / A;
      const int steps = std::max(1, static_cast<int>(std::ceil(r / step)));
      const double dt = r / steps;
      double tau = 0;
      for (int s = 0; s < steps; ++s) {
        const Vec3 x = centers[j] + (s + 0.5) * dt * d;
        // nearest cell centre's sigma_t (the zones are constant)
        int idx[3];
        for (int a = 0; a < 3; ++a)
          idx[a] = std::clamp(static_cast<int>(std::floor((x[a] - g.lower[a]) / h[a])), 0, g.n - 1);
        tau += sol.sigma_t[g.index(idx[0], idx[1], idx[2])] * dt;
      }
      tau -= 0.5 * s_chord * (sol.sigma_t[i] + sol.sigma_t[j]);
      const double T = std::exp(-std::max(0.0, tau));
      F[i * nc + j] = T * A * sigma_i * one_minus_exp_over(sigma_i, s_chord) / (4 * kPi * r * r);
    }
  });

  // Gauss-Seidel on P = omega (P_light + F P).
  std::vector<double> P(nc, 0.0);
  for (int it = 0; it < o.max_iterations; ++it) {
    double change = 0, largest = 0;
    for (std::size_t i = 0; i < nc; ++i) {
      double sum = P_light[i];
      const double* row = &F[i * nc];
      for (std::size_t j = 0; j < nc; ++j) sum += row[j] * P[j];
      const double next = v.albedo * sum;
      change = std::max(change, std::fabs(next - P[i]));
      largest = std::max(largest, std::fabs(next));
      P[i] = next;
    }
    sol.iterations = it + 1;
    if (largest == 0 || change <= o.tolerance * largest) {
      sol.converged = true;
      break;
    }
  }
  sol.multiple.resize(nc);
  for (std::size_t c = 0; c < nc; ++c)
    sol.multiple[c] = std::max(0.0, P[c] - v.albedo * P_light[c]) / (4 * kPi * V);
  sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sol;
}

double gather_zonal(const ScatteringVolume& v, const ZonalSolution& sol, const ViewRay& ray, bool include_single) {
  const Vec3 d = ray.direction.normalized();
  const RayInterval iv = v.density.clip(ViewRay{ray.origin, d});
  const double background = include_single ? v.background : 0.0;
  if (!iv.hit) return background;
  const CellGrid& g = sol.cells;
  const double p_sun = include_single ? v.phase.eval(v.light.direction.dot(-d)) : 0.0;
  const double step = 0.25 * g.h.minCoeff();
  const double len = iv.t_exit - iv.t_enter;
  const int steps = std::max(1, static_cast<int>(std::ceil(len / step)));
  const double dt = len / steps;
  double L = 0, T = 1;
  for (int s = 0; s < steps; ++s) {
    const Vec3 x = ray.origin + (iv.t_enter + (s + 0.5) * dt) * d;
    const double sigma = v.sigma_t(x);
    if (sigma <= 0) continue;
    const double E = g.interpolate(sol.irradiance, x);
    // The zone emission is per unit volume of the zone; spread by sigma_t(x)/sigma_zone so that
    // it follows the medium inside the zone (sigma_zone from the interpolated cell values).
    const double sigma_cells = g.interpolate(sol.sigma_t, x);
    const double multiple = sigma_cells > 0 ? g.interpolate(sol.multiple, x) * sigma / sigma_cells : 0.0;
    const double J = v.albedo * sigma * E * p_sun + multiple;
    const double a1 = one_minus_exp_over(sigma, dt);
    L += T * J * a1;
    T *= 1 - sigma * a1;
  }
  return L + T * background;
}

}  // namespace rayint
