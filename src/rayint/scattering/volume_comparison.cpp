// Discrete ordinates and zonal method against the Monte Carlo reference; see
// volume_comparison.hpp.
#include "rayint/scattering/volume_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rayint/core/parallel.hpp"
#include "rayint/scattering/discrete_ordinates.hpp"
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
  parallel_for(cam.height, threads, [&](std::size_t y) {
    for (int x = 0; x < cam.width; ++x)
      img[y * static_cast<std::size_t>(cam.width) + static_cast<std::size_t>(x)] =
          gather(cam.ray_for_pixel(x, static_cast<int>(y)));
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
// One method's run: times solve() (setup) and the gather of every pixel from its solution, and
// scores the image against the reference.
template <class Solve, class Gather>
MethodRun run_method(const char* method, int grid, int bins, const Camera& cam, unsigned threads,
                     const std::vector<double>& reference, Solve solve, Gather gather) {
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
  r.error = image_error(r.image, reference);
  return r;
}
}  // namespace

VolumeComparison compare_volume_methods(const ScatteringVolume& v, const Camera& cam,
                                        const ComparisonOptions& o,
                                        const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  VolumeComparison c;
  c.width = cam.width;
  c.height = cam.height;
  say("monte carlo, every order");
  PathTracerOptions all = o.reference;
  all.max_order = 0;
  c.reference_all = path_trace_image(v, cam, all);
  say("monte carlo, single scattering with shadows");
  PathTracerOptions single = o.reference;
  single.max_order = 1;
  c.reference_single = path_trace_image(v, cam, single);
  c.mean_reference_se = mean_of(c.reference_all.std_error);
  c.brightness_all = mean_of(c.reference_all.mean);
  c.brightness_single = mean_of(c.reference_single.mean);

  for (int g : o.do_grids)
    for (int b : o.do_bins) {
      say("discrete ordinates grid " + std::to_string(g) + " bins " + std::to_string(6 * b * b));
      DiscreteOrdinatesOptions d;
      d.grid = g;
      d.bins_per_edge = b;
      d.threads = o.threads;
      c.runs.push_back(run_method(
          "discrete_ordinates", g, 6 * b * b, cam, o.threads, c.reference_all.mean,
          [&] { return solve_discrete_ordinates(v, d); },
          [&](const DiscreteOrdinatesSolution& sol, const ViewRay& ray) {
            return gather_discrete_ordinates(v, sol, ray);
          }));
    }
  if (v.phase.kind() == PhaseFunction::Kind::isotropic)
    for (int g : o.zonal_grids) {
      say("zonal grid " + std::to_string(g));
      ZonalOptions z;
      z.grid = g;
      z.threads = o.threads;
      c.runs.push_back(run_method(
          "zonal", g, 0, cam, o.threads, c.reference_all.mean, [&] { return solve_zonal(v, z); },
          [&](const ZonalSolution& sol, const ViewRay& ray) { return gather_zonal(v, sol, ray); }));
    }
  return c;
}

}  // namespace rayint
