#pragma once
// The diffusion (P1) approximation of multiple scattering on a voxel grid, for a ScatteringVolume
// (scattering_volume.hpp): the 3-D form of the slab's P1 (pn.hpp), what volume renderers call
// "diffusion". docs/multiple-scattering.md, "Diffusion (P1) on voxel grids".
//
// 1. Cells and the light's irradiance E at each cell centre: the first pass shared with discrete
//    ordinates and the zonal method (cell_passes.hpp, discrete_ordinates.hpp steps 1-2).
// 2. The scattered field (orders >= 1) in P1 form, L(x, w) = (phi + 3 F . w) / (4 pi), whose
//    source is the light scattered once, Q(x, w) = sigma_s E p(l . w) (l: the light's direction):
//      div F + sigma_a phi = Q0 = sigma_s E,
//      grad phi / 3 + sigma_tr F = Q1 = g sigma_s E l,     sigma_tr = sigma_t - g sigma_s,
//    so F = -D grad phi + Q1 / sigma_tr with D = 1 / (3 sigma_tr), and
//      -div (D grad phi) + sigma_a phi = Q0 - div (Q1 / sigma_tr).
//    Finite volumes on the cells: face diffusion coefficient the harmonic mean of the two cells'
//    D (flux continuity), face source the mean of the two cells' Q1 / sigma_tr. Boundary (the box
//    faces; nothing comes in from outside but the light, which E carries): Marshak's vacuum
//    condition, no inward partial current, J- = phi/4 - F.n/2 = 0, with the boundary value
//    eliminated over the half cell: outward flux (2 D phi_P + h s_n) / (h + 4 D), s_n the face
//    source. The matrix is symmetric positive definite (Marshak's rows add to the diagonal);
//    solved by Eigen's ConjugateGradient with an incomplete-Cholesky preconditioner to a relative
//    residual `tolerance` within `max_iterations` (both reported; converged = false otherwise).
//    The cell flux F is the mean of its two face fluxes per axis.
// 3. Gathering (gather_march, step h/4, as discrete ordinates): the light scattered toward the eye
//    (direction -d for a viewing ray along d) from the P1 field,
//      J = sigma_s(x) (phi - 3 g F . d) / (4 pi)   (exact for any phase function of mean cosine g
//                                                   on a P1 radiance),
//    phi and F trilinear between cell centres, sigma_s at x; plus, if asked, single scattering
//    from E exactly as discrete ordinates does. Orders >= 2 come from the field of orders >= 1.
// Regions and thresholds:
// - Empty space: D = 1 / (3 sigma_tr) is infinite where the medium is absent. sigma_tr is
//   floored at `min_sigma_tr` = kDiffusionMinSigmaFactor / (shortest box edge): across an empty
//   box the floored D carries light as far as a medium of optical size 1 would. Not derived;
//   its effect on the cloud is measured in reports/scattering/diffusion.md.
// - Diffusion is poor where light is not yet diffuse: optically thin media, low albedo, and
//   within a few mean free paths of the boundary or the light's entry (the P1 radiance cannot
//   hold the forward-peaked first orders). Measured against the Monte Carlo on the same grid in
//   reports/scattering/diffusion.md and tests/test_scatter_diffusion.cpp.
#include <vector>

#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/discrete_ordinates.hpp"

namespace rayint {

inline constexpr double kDiffusionMinSigmaFactor = 1.0;
// Largest grid: 128^3 = 2.1e6 unknowns, about 0.6 GB for the matrix, its triplets and the
// preconditioner (7 entries a row; estimated from the entry counts, not measured); a memory
// bound, not an accuracy one.
inline constexpr int kDiffusionMaxGrid = 128;

struct DiffusionOptions {
  int grid = 32;              // cells per axis, 2..kDiffusionMaxGrid
  double tolerance = 1e-10;   // relative residual of the conjugate gradients
  int max_iterations = 5000;
  double min_sigma_factor = kDiffusionMinSigmaFactor;  // sigma_tr floor times the shortest edge
  unsigned threads = 0;       // first pass; 0: all cores
};

struct DiffusionSolution {
  CellGrid cells;
  std::vector<double> sigma_t, irradiance;  // per cell (first pass)
  std::vector<double> fluence;              // phi per cell (orders >= 1)
  std::vector<double> flux_x, flux_y, flux_z;  // F per cell
  int iterations = 0;
  double residual = 0;  // relative, as Eigen reports it
  bool converged = false;
  double seconds = 0;   // setup and solve
};

DiffusionSolution solve_diffusion(const ScatteringVolume& volume, const DiffusionOptions& options);

// Step 3 for one viewing ray; include_single adds order 1 from E and the background.
double gather_diffusion(const ScatteringVolume& volume, const DiffusionSolution& solution, const ViewRay& ray,
                        bool include_single = true);

}  // namespace rayint
