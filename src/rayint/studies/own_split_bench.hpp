#pragma once
// `rayint bench` on a mesh case whose file holds cells other than tetrahedra (issue 29's speed
// target: "a mesh of hexahedra renders at no more than 3x the time of the same mesh split into
// tets"). The sweep (studies/sweep.hpp) needs linear segments, which the cells' own interpolation
// does not give; for such a case bench times instead, on the case's evaluation rays (its "rays",
// or one per camera pixel):
//   own    CellTraversal::trace + CellTraversal::integrate (mesh/cell_traversal.hpp), the cells in
//          their own (isoparametric) interpolation -- what `eval`/`render` compute by default;
//   split  split_cells (VTK's vtkDataSetTriangleFilter rule, mesh/cell_split.hpp), then
//          TetTraversal::trace + ray_from_trace + the `exact` method -- what `--cells split` pays.
// Both single-threaded, the same rays and backgrounds, no reference in the loop. One repetition
// integrates every ray by each path (own, then split: interleaved, so drifting machine load hits
// both alike), each path first once untimed (its data back in the caches, as in a render of one
// mode) and then timed; own_seconds / split_seconds are the MEDIANS over the repetitions of the whole
// ray set's time, as the thread's CPU time (core/cpu_clock.hpp: other jobs on a shared machine
// do not count). Setting up (building the traversal structures; the split itself) is timed
// once, the same way, and reported apart.
//
// The difference between the two answers is the split's error against the own interpolation
// (what tetrahedralisation costs; the own path's own accuracy against the 50-digit reference is
// `rayint eval`'s, reports/cells/accuracy.md): per channel of each ray's intensity
// |I_split - I_own|, and relative |I_split - I_own| / |I_own| (the absolute value where I_own = 0).
// Only rays that both paths integrated count.
//
// Failures are counted, never shown as numbers: a ray whose own integration did not converge
// (CellRayResult::converged) or whose split integral threw or is not finite is failed; the
// differences are then over the other rays (no difference at all when no ray ran on both paths),
// and the ratio own / split is given only when no ray failed (complete()). A mesh that
// split_cells refuses (quadratic cells) has no split: split_failure says why.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "rayint/mesh/mesh_case.hpp"

namespace rayint {

struct OwnSplitBenchOptions {
  int repetitions = 5;  // >= 1; the medians are taken over them
};

struct OwnSplitCase {
  std::string name, source, mesh_source;
  std::vector<std::pair<std::string, long>> cells;  // by type, as read (cell_counts)
  long cell_total = 0;
  bool split_ran = false;       // split_cells accepted the mesh
  std::string split_failure;    // why not, or the first failed ray's reason
  long tets = 0;                // tetrahedra after the split
  bool structured_split = false;  // VTK's structured rule (5 per cell, alternating)
  std::size_t rays = 0;
  int repetitions = 0;
  long own_failed_rays = 0, split_failed_rays = 0;
  std::string own_failure;      // the first failed ray's reason
  long own_chords = 0;          // over the ray set, one pass
  long split_segments = 0;
  double own_seconds = 0.0, split_seconds = 0.0;  // median over repetitions, whole ray set
  double own_setup_seconds = 0.0, split_setup_seconds = 0.0;
  std::size_t compared_rays = 0;  // rays integrated by both paths
  double max_abs_difference = 0.0, max_rel_difference = 0.0;
  std::size_t worst_ray = 0;      // where max_abs_difference occurs
  int worst_channel = 0;

  bool complete() const {
    return split_ran && rays > 0 && own_failed_rays == 0 && split_failed_rays == 0;
  }
  // own_seconds / split_seconds; NaN (shown as null / "-") unless complete() and the split took time.
  double ratio() const {
    return complete() && split_seconds > 0 ? own_seconds / split_seconds : std::numeric_limits<double>::quiet_NaN();
  }
};

// `mesh_case.cells` must be set (std::invalid_argument otherwise).
OwnSplitCase bench_own_vs_split(const MeshCase& mesh_case, const OwnSplitBenchOptions& options);

// Every case, one after the other, with the run's load averages and start time.
struct OwnSplitRun {
  std::vector<OwnSplitCase> cases;
  int repetitions = 0;
  std::array<double, 3> load_start{}, load_end{};  // 1/5/15-minute load averages (-1: unknown)
  std::string started_at;                          // UTC, ISO 8601
};
OwnSplitRun bench_own_cases(const std::vector<MeshCase>& cases, const OwnSplitBenchOptions& options);

}  // namespace rayint
