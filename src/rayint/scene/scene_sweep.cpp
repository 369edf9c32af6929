#include "rayint/scene/scene_sweep.hpp"

#include <chrono>
#include <cmath>

#include "rayint/core/cpu_clock.hpp"
#include "rayint/core/parallel.hpp"

namespace rayint {
namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<long long> subset_of(const Scene& scene, const ScenePipeline& p, int k) {
  std::vector<long long> subset;
  if (!scene.camera) {
    for (long long i = 0; i < p.ray_count(); ++i) subset.push_back(i);
    return subset;
  }
  const int w = scene.camera->width, h = scene.camera->height;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      const int x = std::min(w - 1, static_cast<int>((i + 0.5) * w / k));
      const int y = std::min(h - 1, static_cast<int>((j + 0.5) * h / k));
      subset.push_back(static_cast<long long>(y) * w + x);
    }
  return subset;
}

TermError compare(const std::vector<Rgb>& approx, const std::vector<Rgb>& ref) {
  TermError e;
  double sum = 0;
  for (std::size_t i = 0; i < approx.size(); ++i)
    for (int c = 0; c < kChannels; ++c) {
      const double d = std::abs(approx[i][c] - ref[i][c]);
      e.max_abs = std::max(e.max_abs, d);
      sum += d;
      e.peak_reference = std::max(e.peak_reference, std::abs(ref[i][c]));
    }
  e.rays = static_cast<long long>(approx.size());
  e.mean_abs = approx.empty() ? 0.0 : sum / (3.0 * static_cast<double>(approx.size()));
  e.max_rel_to_peak = e.peak_reference > 0 ? e.max_abs / e.peak_reference : 0.0;
  return e;
}

}  // namespace

SceneSweepResult sweep_scene(const Scene& scene, const std::vector<std::map<std::string, MethodSpec>>& configs,
                        int error_grid, unsigned threads,
                        const std::function<void(std::size_t, std::size_t)>& progress) {
  SceneSweepResult out;
  out.error_grid = error_grid;
  out.threads = resolve_threads(threads);
  const bool absorption = scene.has("absorption");
  // References once, with the scene's own methods (a reference does not depend on the method).
  const ScenePipeline base(scene, threads);
  const std::vector<long long> subset = subset_of(scene, base, error_grid);
  const std::size_t ne = base.effects().size();
  std::vector<std::vector<Rgb>> ref(ne, std::vector<Rgb>(subset.size()));
  std::vector<Rgb> ref_total(subset.size());
  std::vector<std::vector<double>> ref_err(ne, std::vector<double>(subset.size(), 0.0));
  std::vector<char> converged(ne * subset.size(), 1);
  const Clock::time_point t0 = Clock::now();
  parallel_for(static_cast<long long>(subset.size()), threads, [&](long long s, unsigned) {
    const std::size_t i = static_cast<std::size_t>(s);
    const PixelRay pr = base.ray(subset[i]);
    Rgb total = absorption ? Rgb{} : pr.background;
    for (std::size_t e = 0; e < ne; ++e) {
      const ReferenceValue r = base.effects()[e]->reference(pr);
      ref[e][i] = r.value;
      ref_err[e][i] = std::max({r.error_estimate[0], r.error_estimate[1], r.error_estimate[2]});
      converged[e * subset.size() + i] = r.converged ? 1 : 0;
      for (int c = 0; c < kChannels; ++c) total[c] += r.value[c];
    }
    ref_total[i] = total;
  });
  out.reference_seconds = seconds_since(t0);

  for (std::size_t ci = 0; ci < configs.size(); ++ci) {
    Scene variant = scene;
    for (const auto& kv : configs[ci]) variant.methods[kv.first] = kv.second;
    SweepPoint point;
    point.methods = configs[ci];
    const Clock::time_point ts = Clock::now();
    const double cs = process_cpu_seconds();
    const ScenePipeline p(variant, threads);
    point.setup_seconds = seconds_since(ts);
    point.setup_cpu_seconds = process_cpu_seconds() - cs;
    SceneRenderOptions ro;
    ro.threads = threads;
    const SceneRenderResult r = p.render(ro);
    point.render_seconds = r.render_seconds;
    point.render_cpu_seconds = r.render_cpu_seconds;
    point.effects = r.effects;
    // approximations on the subset (untimed)
    std::vector<std::vector<Rgb>> approx(ne, std::vector<Rgb>(subset.size()));
    std::vector<Rgb> total(subset.size());
    parallel_for(static_cast<long long>(subset.size()), threads, [&](long long s, unsigned) {
      const std::size_t i = static_cast<std::size_t>(s);
      const PixelRay pr = p.ray(subset[i]);
      EffectWork w, sw;
      Rgb t = absorption ? Rgb{} : pr.background;
      for (std::size_t e = 0; e < ne; ++e) {
        approx[e][i] = p.effects()[e]->term(pr, w, sw);
        for (int c = 0; c < kChannels; ++c) t[c] += approx[e][i][c];
      }
      total[i] = t;
    });
    for (std::size_t e = 0; e < ne; ++e) {
      TermError te = compare(approx[e], ref[e]);
      for (std::size_t i = 0; i < subset.size(); ++i) {
        te.max_reference_error = std::max(te.max_reference_error, ref_err[e][i]);
        te.reference_converged = te.reference_converged && converged[e * subset.size() + i] != 0;
      }
      point.effects[e].has_error = true;
      point.effects[e].error = te;
    }
    point.total_error = compare(total, ref_total);
    out.points.push_back(point);
    if (progress) progress(ci + 1, configs.size());
  }
  return out;
}

}  // namespace rayint
