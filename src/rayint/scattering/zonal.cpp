// The zonal method for isotropic multiple scattering; see zonal.hpp.
#include "rayint/scattering/zonal.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rayint/core/math.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/scattering/estimate.hpp"
#include "rayint/scattering/cell_passes.hpp"

namespace rayint {

namespace {

// Walks the ray x + t d (x inside the box or on its boundary, d unit) through the zones with
// exact chords (Amanatides & Woo 1987), calling visit(cell, chord) until it leaves the box.
template <class Visit>
void walk_cells(const CellGrid& g, const Vec3& x, const Vec3& d, Visit&& visit) {
  int idx[3], step[3];
  double t_max[3], t_delta[3];
  for (int a = 0; a < 3; ++a) {
    idx[a] = std::clamp(static_cast<int>(std::floor((x[a] - g.lower[a]) / g.h[a])), 0, g.n - 1);
    if (d[a] > 0) {
      step[a] = 1;
      t_max[a] = (g.lower[a] + (idx[a] + 1) * g.h[a] - x[a]) / d[a];
      t_delta[a] = g.h[a] / d[a];
    } else if (d[a] < 0) {
      step[a] = -1;
      t_max[a] = (g.lower[a] + idx[a] * g.h[a] - x[a]) / d[a];
      t_delta[a] = -g.h[a] / d[a];
    } else {
      step[a] = 0;
      t_max[a] = t_delta[a] = std::numeric_limits<double>::infinity();
    }
    t_max[a] = std::max(0.0, t_max[a]);
  }
  double t = 0;
  for (;;) {
    const int a = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    if (!visit(g.index(idx[0], idx[1], idx[2]), t_max[a] - t)) return;
    t = t_max[a];
    idx[a] += step[a];
    if (idx[a] < 0 || idx[a] >= g.n) return;
    t_max[a] += t_delta[a];
  }
}
}  // namespace

ZonalSolution solve_zonal(const ScatteringVolume& v, const ZonalOptions& o) {
  v.validate();
  if (v.phase.kind() != PhaseFunction::Kind::isotropic)
    throw std::invalid_argument("zonal method: isotropic scattering only (phase function is " +
                                std::string(v.phase.name()) + ")");
  if (o.grid < 2 || o.grid > 20) throw std::invalid_argument("zonal method: grid must be in [2, 20]");
  if (o.rays_per_cell < 1 || o.light_rays_per_face < 1)
    throw std::invalid_argument("zonal method: rays_per_cell and light_rays_per_face must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  ZonalSolution sol;
  first_pass(v, o.grid, o.threads, sol);
  const CellGrid& g = sol.cells;
  const std::size_t nc = g.size();
  const Vec3 h = g.h;
  const double V = h[0] * h[1] * h[2];
  const std::vector<double>& sig = sol.sigma_t;

  // Light power extinguished per zone: parallel rays entering through the lit faces.
  std::vector<double> P_light(nc, 0.0);
  const Vec3 d_light = v.light.direction.normalized();
  const int m = o.light_rays_per_face;
  for (int a = 0; a < 3; ++a) {
    if (d_light[a] == 0) continue;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const double face = d_light[a] > 0 ? g.lower[a] : g.upper[a];
    const double dA = (h[b] / m) * (h[c] / m);
    const double power = v.light.irradiance * std::fabs(d_light[a]) * dA;
    for (int ib = 0; ib < g.n * m; ++ib)
      for (int ic = 0; ic < g.n * m; ++ic) {
        Vec3 x;
        x[a] = face;
        x[b] = g.lower[b] + (ib + 0.5) * h[b] / m;
        x[c] = g.lower[c] + (ic + 0.5) * h[c] / m;
        double T = 1;
        walk_cells(g, x, d_light, [&](std::size_t cell, double len) {
          const double absorbed = -std::expm1(-sig[cell] * len);
          P_light[cell] += power * T * absorbed;
          T *= 1 - absorbed;
          return true;
        });
        sol.power_incident += power;
        sol.power_direct += power * T;
      }
  }

  // Exchange factors F(i, j) (row i, column j), column j from rays leaving zone j.
  std::vector<double> F(nc * nc, 0.0);
  sol.escape.assign(nc, 0.0);
  const double w = 1.0 / o.rays_per_cell;
  parallel_for(static_cast<long long>(nc), o.threads, [&](std::size_t jc) {
    if (sig[jc] <= 0) {  // a zone that scatters nothing emits nothing; its column is unused
      sol.escape[jc] = 1;
      return;
    }
    Rng rng = block_rng(o.seed, jc);
    const int ii = static_cast<int>(jc % g.n), jj = static_cast<int>((jc / g.n) % g.n),
              kk = static_cast<int>(jc / (static_cast<std::size_t>(g.n) * g.n));
    const Vec3 corner = g.lower + Vec3(ii * h[0], jj * h[1], kk * h[2]);
    double escaped = 0;
    for (int r = 0; r < o.rays_per_cell; ++r) {
      const Vec3 x = corner + Vec3(rng.uniform() * h[0], rng.uniform() * h[1], rng.uniform() * h[2]);
      const double cz = 2 * rng.uniform() - 1, phi = 2 * kPi * rng.uniform();
      const double sz = std::sqrt(std::max(0.0, 1 - cz * cz));
      const Vec3 d(sz * std::cos(phi), sz * std::sin(phi), cz);
      double T = w;
      walk_cells(g, x, d, [&](std::size_t cell, double len) {
        const double absorbed = -std::expm1(-sig[cell] * len);
        F[cell * nc + jc] += T * absorbed;
        T *= 1 - absorbed;
        return T > 1e-17 * w;  // what is left is below double resolution of the column sum
      });
      escaped += T;
    }
    sol.escape[jc] = escaped;
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
  for (std::size_t i = 0; i < nc; ++i) {
    double inscattered = 0;
    const double* row = &F[i * nc];
    for (std::size_t j = 0; j < nc; ++j) inscattered += row[j] * P[j];
    sol.multiple[i] = v.albedo * inscattered / (4 * kPi * V);
    sol.power_escaped += P[i] * sol.escape[i];
    sol.power_absorbed += (1 - v.albedo) * (P_light[i] + inscattered);
  }
  sol.power = std::move(P);
  sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sol;
}

double gather_zonal(const ScatteringVolume& v, const ZonalSolution& sol, const ViewRay& ray, bool include_single) {
  const CellGrid& g = sol.cells;
  return gather_along(v, g, ray, include_single, [&](const Vec3& x, double sigma, const Vec3&, double p_sun) {
    const double E = g.interpolate(sol.irradiance, x);
    // The zone emission is per unit volume of the zone; spread by sigma_t(x)/sigma_zone so that
    // it follows the medium inside the zone (sigma_zone from the interpolated cell values).
    const double sigma_cells = g.interpolate(sol.sigma_t, x);
    const double multiple = sigma_cells > 0 ? g.interpolate(sol.multiple, x) * sigma / sigma_cells : 0.0;
    return v.albedo * sigma * E * p_sun + multiple;
  });
}

}  // namespace rayint
