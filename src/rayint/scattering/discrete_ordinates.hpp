#pragma once
// Max's discrete-ordinates approximation of multiple scattering on a voxel grid (Max 1995,
// Sec. 7; Max 1994, "Efficient light propagation for multiple anisotropic volume scattering"),
// for a ScatteringVolume (scattering_volume.hpp).
//
// 1. Cells: the volume's box cut into n^3 cells (n = `grid`); sigma_t at each cell centre.
// 2. First pass (Kajiya & Von Herzen's light propagation): the light's irradiance E at each
//    cell centre, exp(-optical depth toward the light) by the midpoint rule with steps of h/4
//    through the trilinear medium.
// 3. Direction bins on the cube faces (direction_bins.hpp), 6 b^2 of them (b = `bins_per_edge`),
//    and the bin-averaged phase matrix.
// 4. Source iteration: the cell source per bin, J_b = sigma_s [E f_b + sum_a L_a Omega_a P_ab] / Omega_b,
//    is propagated along each bin's centre direction by an upwind sweep through the cells (step
//    characteristics: L_out = L_in e^{-sigma s} + J/sigma (1 - e^{-sigma s}), with chord
//    s = 1 / sum_i |d_i|/h_i, the mean chord of the cell along d). The radiance entering a cell is
//    the mix of its upwind neighbours' outgoing radiance weighted by |d_i|/h_i, the share of the
//    flux crossing each face: this is Max's spreading of a bin's flux into the adjacent voxels,
//    which smears the beam over the bin's solid angle instead of shooting narrow rays (the ray
//    effect). Each iteration adds one order; it stops when the largest change of the bin
//    radiances falls below `tolerance` times their largest value, or at `max_iterations`
//    (reported, never silent).
// 5. Final gathering along each viewing ray (midpoint rule, step h/4, trilinear sigma_t):
//    single scattering from the first-pass E (exact phase toward the eye) plus the bins'
//    radiance scattered toward the eye with the phase function integrated over each bin.
// Errors against the Monte Carlo reference are measured, not claimed: reports/scattering/.
#include <vector>

#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/direction_bins.hpp"
#include "rayint/scattering/scattering_volume.hpp"

namespace rayint {

struct DiscreteOrdinatesOptions {
  int grid = 32;            // cells per axis
  int bins_per_edge = 3;    // 6 b^2 direction bins
  int sub_per_edge = 4;     // phase-function sub-directions per bin edge
  int max_iterations = 300;
  double tolerance = 1e-5;
  int max_order = 0;        // 0: iterate to convergence; 1: single scattering only
  unsigned threads = 0;  // 0: all cores
};

// Cell-centred fields on n^3 cells over the volume's box, x fastest.
struct CellGrid {
  int n = 0;
  Vec3 lower, upper, h;
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(n) * static_cast<std::size_t>(k));
  }
  std::size_t size() const { return static_cast<std::size_t>(n) * n * n; }
  Vec3 center(int i, int j, int k) const {
    return lower + Vec3((i + 0.5) * h[0], (j + 0.5) * h[1], (k + 0.5) * h[2]);
  }
  // Trilinear interpolation of cell-centred values at x (clamped to the outermost centres).
  double interpolate(const std::vector<double>& f, const Vec3& x) const;
  double interpolate(const std::vector<float>& f, std::size_t stride, std::size_t offset,
                     const Vec3& x) const;
};

CellGrid make_cell_grid(const ScatteringVolume& volume, int n);

// Light irradiance at every cell centre (step 2); shared with the zonal method.
std::vector<double> first_pass_irradiance(const ScatteringVolume& volume, const CellGrid& cells,
                                          unsigned threads);

struct DiscreteOrdinatesSolution {
  CellGrid cells;
  std::vector<DirectionBin> bins;
  std::vector<double> sigma_t;     // per cell
  std::vector<double> irradiance;  // per cell (first pass)
  std::vector<float> radiance;     // per cell and bin (cell-averaged), index cell * bins + b
  int iterations = 0;
  bool converged = false;
  double last_change = 0;          // relative
  double seconds = 0;
};

DiscreteOrdinatesSolution solve_discrete_ordinates(const ScatteringVolume& volume,
                                                   const DiscreteOrdinatesOptions& options);

// Step 5 for one viewing ray (origin, direction from the eye).
double gather_discrete_ordinates(const ScatteringVolume& volume,
                                 const DiscreteOrdinatesSolution& solution, const ViewRay& ray,
    bool include_single = true);

}  // namespace rayint
