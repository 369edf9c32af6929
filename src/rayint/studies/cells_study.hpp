#pragma once
// How far the linear-tetrahedra route (decompose, then `exact`) lies from the truth for the
// higher-order cells of Williams & Max (1992, appendix) and for trilinear voxel grids, and
// what the polynomial-scalar ODE achieves. The truth is the 50-digit polynomial reference
// (reference/poly_reference.hpp). `rayint cells` prints this; tests [cells] run it small and
// assert the order of convergence, so the report and the test measure the same thing.
//
// Samples. Per cell type: `count` random undistorted cells (tet10: the unit corner tet with
// corners moved by up to +-0.2 per coordinate, |det| >= 0.05; bricks: half-axes 0.5 I moved by
// up to +-0.1 per entry), node values uniform in [0, 1], six random transfer functions on
// [0, 1] (2-5 points each, rho in [0, 4], kappa in [0, 1]), and `rays_per_cell` rays through two
// uniform random interior points, background (0.2, 0.5, 0.8). Voxel grids: the unit box with
// random node values (`voxel_random_points` per axis) and a smooth field
// 0.5 + 0.3 sin(2x + 1) cos(3y) + 0.2 z^2 at each of `voxel_sizes`, `voxel_rays` random rays
// each, transfer functions as above. Every sample is seeded from (seed, kind, index), so runs
// are reproducible whatever the thread count.
// Error of a ray: the largest relative error of the intensity over the three channels.
// Times: CPU time of the worker thread per ray (robust to machine load); `seconds` is wall time.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rayint/cells/cell.hpp"
#include "rayint/core/shard.hpp"
#include "rayint/core/statistics.hpp"  // ErrorStats, error_stats
#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct CellsStudyOptions {
  int count = 50;  // random cells per type
  std::uint64_t seed = 1;
  int rays_per_cell = 2;
  std::vector<int> levels{1, 2, 4, 8};  // sub-cells per edge
  double ode_rtol = 1e-8;
  int voxel_random_points = 8;
  std::vector<int> voxel_sizes{4, 8, 16};
  int voxel_rays = 20;
  unsigned threads = 1;  // 0: all cores
  std::function<void(const std::string&)> progress;  // may be empty; called from one thread
};

struct LevelResult {
  int level = 0;
  ErrorStats rel;                  // decomposed + exact against the reference
  double segments_per_ray = 0.0;   // linear segments exact integrated
  double decompose_us_per_ray = 0.0;
  double exact_us_per_ray = 0.0;
};

struct CellTypeResult {
  std::string type;
  int samples = 0;  // rays
  std::vector<LevelResult> levels;
  // Order p of error ~ level^-p: least squares over all levels of log(median) and log(max),
  // and per doubling log2(median(n) / median(2n)).
  double order_median = 0.0, order_max = 0.0;
  std::vector<double> order_steps;
  ErrorStats ode_rel;  // polynomial-scalar ODE at ode_rtol against the reference
  double ode_us_per_ray = 0.0, ode_steps_per_ray = 0.0;
  double reference_ms_per_ray = 0.0, pieces_per_ray = 0.0;
  double max_reference_bound_rel = 0.0;  // largest error bound / intensity of the reference
};

struct VoxelResult {
  std::string field;  // "random" or "smooth"
  int points_per_axis = 0;
  int samples = 0;
  ErrorStats rel;  // Kuhn segments + exact against the trilinear reference
  double segments_per_ray = 0.0, exact_us_per_ray = 0.0, reference_ms_per_ray = 0.0;
};

struct CellsReport {
  CellsStudyOptions options;
  std::vector<CellTypeResult> cells;
  std::vector<VoxelResult> voxels;
  double seconds = 0.0;
};

CellsReport run_cells_study(const CellsStudyOptions& options);

// What one ray measured (the summaries above are means, ErrorStats and fits over these).
struct CellRaySample {  // a ray through a higher-order cell
  std::vector<double> level_error, level_segments, level_decompose_s, level_exact_s;  // per level
  double ode_error = 0, ode_s = 0, ode_steps = 0, reference_s = 0, pieces = 0, bound_rel = 0;
};
struct VoxelRaySample {  // a ray through a voxel grid
  double error = 0, segments = 0, exact_s = 0, reference_s = 0;
};

// `--shard I/N` (README, "Shards and merge"): the samples of a part of the study. Shard I owns,
// per cell type, the cells shard_range(count, I/N) (with all their rays) and, per voxel grid,
// the rays shard_range(voxel_rays, I/N); every sample is seeded from (seed, kind, index) as in
// the whole run, so the shards' samples are exactly the whole run's.
struct CellsSamples {
  std::vector<std::vector<CellRaySample>> cells;    // tet10, hex8, hex20: rays in order
  std::vector<std::vector<VoxelRaySample>> voxels;  // random grid, then each of voxel_sizes
  double seconds = 0.0;                             // wall time of the part
};
CellsSamples run_cells_samples(const CellsStudyOptions& options, const ShardSpec& shard);
// The report from the parts in shard order (the whole run is the single whole part): the
// samples concatenated, then summarised as the single run does, so every figure but the times
// is identical; a time is the same mean over the same measured samples, `seconds` the sum.
CellsReport finish_cells_study(const CellsStudyOptions& options, const std::vector<CellsSamples>& parts);

// The sample generators, exposed for tests.
HigherOrderCell random_cell(CellType type, std::uint64_t seed);
TransferFunctions random_transfer_functions(std::uint64_t seed);
ViewRay random_ray_through(const HigherOrderCell& cell, std::uint64_t seed);

}  // namespace rayint
