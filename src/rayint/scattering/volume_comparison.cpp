// Discrete ordinates and zonal method against the Monte Carlo reference; see
// volume_comparison.hpp.
#include "rayint/scattering/volume_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rayint/core/parallel.hpp"
#include "rayint/scattering/discrete_ordinates.hpp"
#include "rayint/scattering/diffusion.hpp"
#include "rayint/scattering/zonal.hpp"

namespace rayint {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

template <class Gather>
std::vector<double> gather_image(const Camera& cam, unsigned threads, Gather gather) {
  std::vector<double> img(static_cast<std::size_t>(cam.width) * cam.height);
  const CameraRays camera_rays(cam);  // the camera's frame once, the rays its bits
  parallel_for(cam.height, threads, [&](std::size_t y) {
    for (int x = 0; x < cam.width; ++x)
      img[y * static_cast<std::size_t>(cam.width) + static_cast<std::size_t>(x)] =
          gather(camera_rays.ray_for_pixel(x, static_cast<int>(y)));
  });
  return img;
}
}  // namespace

ImageError image_error(const std::vector<double>& image, const std::vector<double>& ref) {
  ImageError e;
  double s2 = 0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const double d = std::fabs(image[i] - ref[i]);
    e.mean_abs += d;
    s2 += d * d;
    e.max_abs = std::max(e.max_abs, d);
  }
  const double n = static_cast<double>(image.size());
  e.mean_abs /= n;
  e.rms = std::sqrt(s2 / n);
  const double mr = mean_of(ref);
  e.mean_rel_brightness = mr > 0 ? (mean_of(image) - mr) / mr : 0.0;
  return e;
}

namespace {
// One method's run: times solve() (setup) and the gather of every pixel from its solution (the
// image is scored against the reference in finish_volume_comparison).
template <class Solve, class Gather>
MethodRun run_method(const char* method, int grid, int bins, const Camera& cam, unsigned threads,
                     Solve solve, Gather gather) {
  MethodRun r;
  r.method = method;
  r.grid = grid;
  r.bins = bins;
  const auto t0 = Clock::now();
  const auto sol = solve();
  r.setup_seconds = since(t0);
  r.iterations = sol.iterations;
  r.converged = sol.converged;
  const auto t1 = Clock::now();
  r.image = gather_image(cam, threads, [&](const ViewRay& ray) { return gather(sol, ray); });
  r.gather_seconds = since(t1);
  return r;
}

// A method's options (DiscreteOrdinatesOptions, ZonalOptions, DiffusionOptions) for one run: its
// grid, and the comparison's threads.
template <class Options>
Options on_grid(int grid, unsigned threads) {
  Options options;
  options.grid = grid;
  options.threads = threads;
  return options;
}
}  // namespace

namespace {

// One entry of the run list: discrete ordinates (grid, bins per edge), zonal (grid, 0) or
// diffusion (grid, 0).
struct PlannedRun {
  bool zonal = false;
  int grid = 0, bins_per_edge = 0;
  bool diffusion = false;
};

std::vector<PlannedRun> planned_runs(const ScatteringVolume& v, const ComparisonOptions& o) {
  std::vector<PlannedRun> out;
  for (int g : o.do_grids)
    for (int b : o.do_bins) out.push_back({false, g, b});
  if (v.phase.kind() == PhaseFunction::Kind::isotropic)
    for (int g : o.zonal_grids) out.push_back({true, g, 0});
  for (int g : o.diffusion_grids) out.push_back({false, g, 0, true});
  return out;
}

}  // namespace

std::size_t volume_run_count(const ScatteringVolume& v, const ComparisonOptions& o) {
  return planned_runs(v, o).size();
}

VolumeComparisonPart compare_volume_methods_part(const ScatteringVolume& v, const Camera& cam,
                                                 const ComparisonOptions& o, const ShardSpec& shard,
                                                 const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  VolumeComparisonPart part;
  part.width = cam.width;
  part.height = cam.height;
  const IndexRange rows = shard_range(static_cast<std::size_t>(cam.height), shard);
  part.row_begin = static_cast<int>(rows.begin);
  part.row_end = static_cast<int>(rows.end);
  say("monte carlo, every order");
  PathTracerOptions all = o.reference;
  all.max_order = 0;
  part.reference_all = path_trace_rows(v, cam, all, part.row_begin, part.row_end);
  say("monte carlo, single scattering with shadows");
  PathTracerOptions single = o.reference;
  single.max_order = 1;
  part.reference_single = path_trace_rows(v, cam, single, part.row_begin, part.row_end);

  const std::vector<PlannedRun> plan = planned_runs(v, o);
  const IndexRange mine = shard_range(plan.size(), shard);
  for (std::size_t k = mine.begin; k < mine.end; ++k) {
    const PlannedRun& p = plan[k];
    MethodRun r;
    if (p.diffusion) {
      say("diffusion grid " + std::to_string(p.grid));
      const auto df = on_grid<DiffusionOptions>(p.grid, o.threads);
      r = run_method(
          "diffusion", p.grid, 0, cam, o.threads, [&] { return solve_diffusion(v, df); },
          [&](const DiffusionSolution& sol, const ViewRay& ray) { return gather_diffusion(v, sol, ray); });
    } else if (!p.zonal) {
      const int g = p.grid, b = p.bins_per_edge;
      say("discrete ordinates grid " + std::to_string(g) + " bins " + std::to_string(6 * b * b));
      auto d = on_grid<DiscreteOrdinatesOptions>(g, o.threads);
      d.bins_per_edge = b;
      r = run_method(
          "discrete_ordinates", g, 6 * b * b, cam, o.threads, [&] { return solve_discrete_ordinates(v, d); },
          [&](const DiscreteOrdinatesSolution& sol, const ViewRay& ray) {
            return gather_discrete_ordinates(v, sol, ray);
          });
    } else {
      say("zonal grid " + std::to_string(p.grid));
      const auto z = on_grid<ZonalOptions>(p.grid, o.threads);
      r = run_method(
          "zonal", p.grid, 0, cam, o.threads, [&] { return solve_zonal(v, z); },
          [&](const ZonalSolution& sol, const ViewRay& ray) { return gather_zonal(v, sol, ray); });
    }
    part.run_index.push_back(k);
    part.runs.push_back(std::move(r));
  }
  return part;
}

VolumeComparison finish_volume_comparison(const std::vector<VolumeComparisonPart>& parts) {
  if (parts.empty()) throw std::invalid_argument("scatter merge: no parts");
  VolumeComparison c;
  c.width = parts.front().width;
  c.height = parts.front().height;
  const std::size_t w = static_cast<std::size_t>(c.width), n = w * static_cast<std::size_t>(c.height);
  for (EstimateImage* img : {&c.reference_all, &c.reference_single}) {
    img->width = c.width;
    img->height = c.height;
    img->mean.assign(n, 0.0);
    img->std_error.assign(n, 0.0);
  }
  std::vector<std::pair<std::size_t, const MethodRun*>> runs;
  for (const VolumeComparisonPart& p : parts) {
    if (p.width != c.width || p.height != c.height || p.row_begin < 0 || p.row_begin > p.row_end ||
        p.row_end > c.height || p.run_index.size() != p.runs.size())
      throw std::invalid_argument("scatter merge: a part's image size, rows or runs do not fit the run");
    const std::size_t rows = static_cast<std::size_t>(p.row_end - p.row_begin);
    const std::size_t at = static_cast<std::size_t>(p.row_begin) * w;
    for (auto [from, to] : {std::pair{&p.reference_all, &c.reference_all},
                            std::pair{&p.reference_single, &c.reference_single}}) {
      if (from->mean.size() != rows * w || from->std_error.size() != rows * w)
        throw std::invalid_argument("scatter merge: a part's reference holds the wrong number of pixels");
      std::copy(from->mean.begin(), from->mean.end(), to->mean.begin() + static_cast<std::ptrdiff_t>(at));
      std::copy(from->std_error.begin(), from->std_error.end(), to->std_error.begin() + static_cast<std::ptrdiff_t>(at));
      to->stats.paths += from->stats.paths;
      to->stats.real_collisions += from->stats.real_collisions;
      to->stats.tentative_collisions += from->stats.tentative_collisions;
      to->stats.shadow_rays += from->stats.shadow_rays;
      to->stats.seconds += from->stats.seconds;
    }
    for (std::size_t k = 0; k < p.runs.size(); ++k) {
      if (p.runs[k].image.size() != n)
        throw std::invalid_argument("scatter merge: a run's image holds the wrong number of pixels");
      runs.emplace_back(p.run_index[k], &p.runs[k]);
    }
  }
  std::sort(runs.begin(), runs.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  c.mean_reference_se = mean_of(c.reference_all.std_error);
  c.brightness_all = mean_of(c.reference_all.mean);
  c.brightness_single = mean_of(c.reference_single.mean);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (k > 0 && runs[k].first == runs[k - 1].first)
      throw std::invalid_argument("scatter merge: method run " + std::to_string(runs[k].first) + " twice");
    MethodRun r = *runs[k].second;
    r.error = image_error(r.image, c.reference_all.mean);
    c.runs.push_back(std::move(r));
  }
  return c;
}

VolumeComparison compare_volume_methods(const ScatteringVolume& v, const Camera& cam,
                                        const ComparisonOptions& o,
                                        const std::function<void(const std::string&)>& progress) {
  return finish_volume_comparison({compare_volume_methods_part(v, cam, o, ShardSpec{}, progress)});
}

}  // namespace rayint
