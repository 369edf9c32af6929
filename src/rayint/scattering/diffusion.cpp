// The diffusion (P1) approximation on a voxel grid; see diffusion.hpp.
#include "rayint/scattering/diffusion.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/core/math.hpp"
#include "rayint/scattering/cell_passes.hpp"

namespace rayint {

DiffusionSolution solve_diffusion(const ScatteringVolume& v, const DiffusionOptions& o) {
  v.validate();
  if (o.grid < 2 || o.grid > kDiffusionMaxGrid)
    throw std::invalid_argument("diffusion: grid must be in [2, " + std::to_string(kDiffusionMaxGrid) +
                                "] cells per axis, got " + std::to_string(o.grid));
  if (!(o.tolerance > 0) || o.max_iterations < 1)
    throw std::invalid_argument("diffusion: tolerance must be > 0 and max_iterations >= 1");
  if (!(o.min_sigma_factor > 0)) throw std::invalid_argument("diffusion: min_sigma_factor must be > 0");
  const auto t0 = std::chrono::steady_clock::now();
  DiffusionSolution sol;
  first_pass(v, o.grid, o.threads, sol);
  const CellGrid& g = sol.cells;
  const int n = g.n;
  const std::size_t cells = g.size();
  const double omega = v.albedo, gbar = v.phase.mean_cosine();
  const double floor = o.min_sigma_factor / (g.upper - g.lower).minCoeff();
  const Vec3 l = v.light.direction.normalized();

  // Per cell: D, sigma_a, Q0 and the source term s = Q1 / sigma_tr (a vector).
  std::vector<double> D(cells), sigma_a(cells), q0(cells);
  std::vector<std::array<double, 3>> s(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    const double st = sol.sigma_t[c], ss = omega * st;
    const double str = std::max(st - gbar * ss, floor);
    D[c] = 1 / (3 * str);
    sigma_a[c] = st - ss;
    q0[c] = ss * sol.irradiance[c];
    for (int a = 0; a < 3; ++a) s[c][static_cast<std::size_t>(a)] = gbar * q0[c] * l[a] / str;
  }

  // Rows per unit cell volume: sum over faces of the outward flux / h_a + sigma_a phi = Q0.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(7 * cells);
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(cells));
  const int step[3] = {1, n, n * n};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int ijk[3] = {i, j, k};
        const std::size_t P = g.index(i, j, k);
        double diag = sigma_a[P], b = q0[P];
        for (int a = 0; a < 3; ++a) {
          const double h = g.h[a];
          const auto ua = static_cast<std::size_t>(a);
          for (int side : {-1, 1}) {
            const int m = ijk[a] + side;
            if (m < 0 || m >= n) {
              // Marshak: outward flux (2 D phi_P + h s_n) / (h + 4 D).
              const double sn = side * s[P][ua];
              diag += 2 * D[P] / ((h + 4 * D[P]) * h);
              b -= sn / (h + 4 * D[P]);
              continue;
            }
            const std::size_t N = static_cast<std::size_t>(static_cast<long>(P) + side * step[a]);
            const double Df = 2 * D[P] * D[N] / (D[P] + D[N]);
            const double c = Df / (h * h);
            diag += c;
            entries.emplace_back(static_cast<int>(P), static_cast<int>(N), -c);
            b -= side * 0.5 * (s[P][ua] + s[N][ua]) / h;
          }
        }
        entries.emplace_back(static_cast<int>(P), static_cast<int>(P), diag);
        rhs(static_cast<Eigen::Index>(P)) = b;
      }
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(cells), static_cast<Eigen::Index>(cells));
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double>>
      cg;
  cg.setTolerance(o.tolerance);
  cg.setMaxIterations(o.max_iterations);
  cg.compute(A);
  if (cg.info() != Eigen::Success) throw std::runtime_error("diffusion: the preconditioner failed");
  const Eigen::VectorXd phi = cg.solve(rhs);
  sol.iterations = static_cast<int>(cg.iterations());
  sol.residual = cg.error();
  sol.converged = cg.info() == Eigen::Success && sol.residual <= o.tolerance;
  sol.fluence.assign(phi.data(), phi.data() + phi.size());

  // Cell flux: the mean of the two face fluxes per axis (in the +axis direction).
  sol.flux_x.assign(cells, 0.0);
  sol.flux_y.assign(cells, 0.0);
  sol.flux_z.assign(cells, 0.0);
  std::vector<double>* flux[3] = {&sol.flux_x, &sol.flux_y, &sol.flux_z};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int ijk[3] = {i, j, k};
        const std::size_t P = g.index(i, j, k);
        for (int a = 0; a < 3; ++a) {
          const double h = g.h[a];
          const auto ua = static_cast<std::size_t>(a);
          double sum = 0;
          for (int side : {-1, 1}) {
            const int m = ijk[a] + side;
            double outward;
            if (m < 0 || m >= n) {
              outward = (2 * D[P] * sol.fluence[P] + h * side * s[P][ua]) / (h + 4 * D[P]);
            } else {
              const std::size_t N = static_cast<std::size_t>(static_cast<long>(P) + side * step[a]);
              const double Df = 2 * D[P] * D[N] / (D[P] + D[N]);
              outward = Df * (sol.fluence[P] - sol.fluence[N]) / h + side * 0.5 * (s[P][ua] + s[N][ua]);
            }
            sum += side * outward;  // the +axis component
          }
          (*flux[a])[P] = 0.5 * sum;
        }
      }
  bool finite = true;
  for (std::size_t c = 0; c < cells; ++c) finite = finite && std::isfinite(sol.fluence[c]);
  if (!finite) throw std::runtime_error("diffusion: the solve produced a non-finite fluence");
  sol.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sol;
}

double gather_diffusion(const ScatteringVolume& v, const DiffusionSolution& sol, const ViewRay& ray,
                        bool include_single) {
  const CellGrid& g = sol.cells;
  const double gbar = v.phase.mean_cosine();
  return gather_along(v, g, ray, include_single, [&](const Vec3& x, double sigma, const Vec3& d, double p_sun) {
    const double E = include_single ? g.interpolate(sol.irradiance, x) : 0.0;
    const double Fd = g.interpolate(sol.flux_x, x) * d[0] + g.interpolate(sol.flux_y, x) * d[1] +
                      g.interpolate(sol.flux_z, x) * d[2];
    const double phi = g.interpolate(sol.fluence, x);
    return v.albedo * sigma * (E * p_sun + (phi - 3 * gbar * Fd) / (4 * kPi));
  });
}

}  // namespace rayint
