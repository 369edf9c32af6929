// `rayint bench` on cells other than tetrahedra: own interpolation against VTK's split
// (see own_split_bench.hpp).
#include "rayint/studies/own_split_bench.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <stdexcept>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/cpu_clock.hpp"
#include "rayint/core/statistics.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/studies/sweep.hpp"  // load_average, utc_now

namespace rayint {
namespace {

// Thread CPU time (core/cpu_clock.hpp): on a shared, oversubscribed machine wall time counts
// other jobs' slices; the single-threaded passes' CPU time does not.
double seconds_since(double start) { return thread_cpu_seconds() - start; }

// One ray's answer by one path: its intensity, or why it has none.
struct PathAnswer {
  bool ok = false;
  Rgb intensity{};
  std::string failure;
};

bool finite(const Rgb& c) { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }

}  // namespace

OwnSplitCase bench_own_vs_split(const MeshCase& mc, const OwnSplitBenchOptions& options) {
  if (!mc.cells) throw std::invalid_argument(mc.source + ": not a mesh case of cells in their own interpolation");
  if (options.repetitions < 1) throw std::invalid_argument("bench: repetitions must be >= 1");
  OwnSplitCase out;
  out.name = mc.name;
  out.source = mc.source;
  out.mesh_source = mc.mesh_source;
  out.repetitions = options.repetitions;
  const std::vector<MeshViewRay> rays = evaluation_rays(mc);
  out.rays = rays.size();

  double start = thread_cpu_seconds();
  const CellTraversal own_mesh(*mc.cells, mc.mesh_source);
  const LinearCellIntegrator own_integrator(mc.transfer);
  out.own_setup_seconds = seconds_since(start);
  out.cells = cell_counts(own_mesh.mesh());
  for (const auto& [type, n] : out.cells) out.cell_total += n;

  // The split: quadratic cells are refused by split_cells (std::invalid_argument / InputError).
  std::unique_ptr<TetTraversal> split_mesh;
  std::unique_ptr<RayIntegrator> exact;
  try {
    start = thread_cpu_seconds();
    for (std::size_t c = 0; c < mc.cells->cell_count(); ++c)  // VTK's split of them is not reproduced
      if (is_quadratic(mc.cells->types[c]))
        throw std::invalid_argument(quadratic_split_message(static_cast<int>(mc.cells->types[c])));
    CellSplitCounts counts;
    TetMesh tets = split_cells(*mc.cells, &counts);
    repair_tet_mesh(tets, mc.mesh_source);  // as `--cells split` reads it (orientation; degenerate dropped)
    out.tets = static_cast<long>(tets.tets.size());
    out.structured_split = counts.structured;
    split_mesh = std::make_unique<TetTraversal>(std::move(tets), mc.mesh_source + " (split)");
    exact = make_integrator(parse_method_spec("exact"), mc.transfer);
    out.split_setup_seconds = seconds_since(start);
    out.split_ran = true;
  } catch (const std::exception& e) {
    out.split_failure = e.what();
  }

  std::vector<PathAnswer> own(rays.size()), split(rays.size());
  std::vector<double> own_times, split_times;
  CellTrace cell_trace;
  RayTrace tet_trace;
  Ray ray;
  // One pass of each path over every ray; `record` keeps the answers (the same every pass).
  const auto own_pass = [&](bool record) {
    const double start_pass = thread_cpu_seconds();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      try {  // a throw is that ray's failure, as in the split pass
        own_mesh.trace(rays[i].ray, cell_trace);
        const CellRayResult r = own_mesh.integrate(cell_trace, own_integrator, rays[i].background);
        if (!record) continue;
        out.own_chords += r.chords;
        own[i].ok = r.converged && finite(r.intensity);
        own[i].intensity = r.intensity;
        own[i].failure = r.converged ? (own[i].ok ? "" : "non-finite intensity") : r.failure;
      } catch (const std::exception& e) {
        if (record) own[i].failure = e.what();
      }
    }
    return seconds_since(start_pass);
  };
  const auto split_pass = [&](bool record) {
    const double start_pass = thread_cpu_seconds();
    for (std::size_t i = 0; i < rays.size(); ++i) {
      try {
        split_mesh->trace(rays[i].ray, tet_trace);
        ray_from_trace(tet_trace, rays[i].background, ray);
        const RayResult r = exact->integrate(ray, nullptr);
        if (!record) continue;
        out.split_segments += static_cast<long>(ray.segments.size());
        split[i].ok = finite(r.intensity);
        split[i].intensity = r.intensity;
        if (!split[i].ok) split[i].failure = "non-finite intensity";
      } catch (const std::exception& e) {
        if (record) split[i].failure = e.what();
      }
    }
    return seconds_since(start_pass);
  };
  // Each repetition: own untimed, own timed, split untimed, split timed -- every timed pass right
  // after an untimed one of the same path, its data in the caches as in a render of one mode
  // (timing the split right after the own path read it ~1.4x slower than BM_mesh/split).
  for (int rep = 0; rep < options.repetitions; ++rep) {
    own_pass(rep == 0);
    own_times.push_back(own_pass(false));
    if (!split_mesh) continue;
    split_pass(rep == 0);
    split_times.push_back(split_pass(false));
  }
  out.own_seconds = median(own_times);
  out.split_seconds = median(split_times);

  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (!own[i].ok) {
      if (out.own_failed_rays++ == 0) out.own_failure = own[i].failure;
    }
    if (split_mesh && !split[i].ok) {
      if (out.split_failed_rays++ == 0) out.split_failure = split[i].failure;
    }
    if (!own[i].ok || !split[i].ok) continue;
    ++out.compared_rays;
    for (int c = 0; c < 3; ++c) {
      const double a = own[i].intensity[static_cast<std::size_t>(c)], b = split[i].intensity[static_cast<std::size_t>(c)];
      const double d = std::fabs(b - a), rel = a != 0.0 ? d / std::fabs(a) : d;
      if (d > out.max_abs_difference) {
        out.max_abs_difference = d;
        out.worst_ray = i;
        out.worst_channel = c;
      }
      out.max_rel_difference = std::max(out.max_rel_difference, rel);
    }
  }
  return out;
}

OwnSplitRun bench_own_cases(const std::vector<MeshCase>& cases, const OwnSplitBenchOptions& options) {
  OwnSplitRun run;
  run.repetitions = options.repetitions;
  run.started_at = utc_now();
  run.load_start = load_average();
  for (const MeshCase& mc : cases) run.cases.push_back(bench_own_vs_split(mc, options));
  run.load_end = load_average();
  return run;
}

}  // namespace rayint
