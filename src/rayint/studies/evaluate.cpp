#include "rayint/studies/evaluate.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "rayint/core/parallel.hpp"
#include "rayint/core/statistics.hpp"
#include "rayint/metrics/error_metrics.hpp"

namespace rayint {

void score_against_reference(MethodOutcome& o, const ReferenceRay& ref) {
  o.finite = true;
  for (int c = 0; c < kChannels; ++c) {
    const double I = o.result.intensity[c];
    const double tr = o.result.transmittance[c];
    if (!std::isfinite(I) || !std::isfinite(tr)) o.finite = false;
    o.abs_error[c] = absolute_error(I, ref.intensity[c]);
    o.rel_error[c] = relative_error(I, ref.intensity[c]);
    o.ulp_error[c] = ulp_error(I, ref.intensity[c]);
    o.transmittance_rel_error[c] = relative_error(tr, ref.transmittance[c]);
  }
}

double time_per_ray(const RayIntegrator& integrator, const Ray& ray, const EvalOptions& opt) {
  using clock = std::chrono::steady_clock;
  std::vector<double> samples;
  volatile double sink = 0.0;
  for (int batch = 0; batch < std::max(1, opt.timing_batches); ++batch) {
    long reps = 0;
    const auto start = clock::now();
    double elapsed = 0.0;
    do {
      sink = sink + integrator.integrate(ray, nullptr).intensity[0];
      ++reps;
      elapsed = std::chrono::duration<double>(clock::now() - start).count();
    } while (elapsed < opt.timing_batch_seconds);
    samples.push_back(elapsed / static_cast<double>(reps));
  }
  return median(samples);
}

std::vector<ReferenceRay> reference_rays(
    const Case& c, unsigned threads,
    const std::function<void(std::size_t done, std::size_t total)>& progress,
    double progress_seconds) {
  std::vector<ReferenceRay> refs(c.rays.size());
  std::size_t total = 0;
  for (const Ray& ray : c.rays) total += ray.segments.size();
  if (c.rays.size() >= resolve_threads(threads)) {  // over the rays
    std::atomic<std::size_t> done{0};
    const auto one = [&](long long i) {
      const auto r = static_cast<std::size_t>(i);
      refs[r] = reference_ray(c.transfer, c.rays[r]);
      done += c.rays[r].segments.size();
    };
    const auto n = static_cast<long long>(c.rays.size());
    if (progress && parallel_workers(n, threads) > 1)
      parallel_for(n, threads, one, progress_seconds, [&] { progress(done.load(), total); });
    else
      parallel_for(n, threads, one);
    if (progress) progress(total, total);
    return refs;
  }
  std::size_t before = 0;  // over the segments of each ray in turn
  for (std::size_t r = 0; r < c.rays.size(); ++r) {
    ReferenceRun run;
    run.threads = threads;
    if (progress)
      run.progress = [&](std::size_t done, std::size_t) { progress(before + done, total); };
    refs[r] = reference_ray(c.transfer, c.rays[r], run);
    before += c.rays[r].segments.size();
  }
  return refs;
}

CaseEvaluation evaluate_case(const Case& c, const std::vector<MethodSpec>& methods,
                             const EvalOptions& opt) {
  CaseEvaluation out{c.name, c.description, c.source, {}, opt.with_reference, {}};
  std::vector<ReferenceRay> refs(c.rays.size());
  if (opt.with_reference) {
    std::function<void(std::size_t, std::size_t)> tick;
    if (opt.progress)
      tick = [&](std::size_t done, std::size_t total) {
        opt.progress(EvalProgress{EvalProgress::Stage::reference, done, total, {}});
      };
    refs = reference_rays(c, opt.threads, tick, opt.progress_seconds);
  }
  std::vector<std::unique_ptr<RayIntegrator>> integrators;
  std::vector<std::string> build_errors;
  for (const auto& spec : methods) {
    try {
      integrators.push_back(make_integrator(spec, c.transfer));
      build_errors.emplace_back();
    } catch (const std::exception& e) {
      integrators.push_back(nullptr);
      build_errors.emplace_back(e.what());
    }
  }
  for (std::size_t r = 0; r < c.rays.size(); ++r) {
    RayEvaluation ev;
    ev.reference = refs[r];
    for (std::size_t m = 0; m < methods.size(); ++m) {
      MethodOutcome o;
      o.method = methods[m].label();
      if (opt.progress)
        opt.progress(EvalProgress{EvalProgress::Stage::methods, r, c.rays.size(), o.method});
      if (!integrators[m]) {
        o.failure = build_errors[m];
        o.finite = false;
        ev.methods.push_back(std::move(o));
        continue;
      }
      try {
        o.result = integrators[m]->integrate(c.rays[r], &o.diagnostics);
        if (opt.with_reference) {
          score_against_reference(o, ev.reference);
        } else {
          o.finite = true;
          for (int ch = 0; ch < kChannels; ++ch)
            if (!std::isfinite(o.result.intensity[ch]) || !std::isfinite(o.result.transmittance[ch]))
              o.finite = false;
        }
        if (opt.measure_time) o.seconds_per_ray = time_per_ray(*integrators[m], c.rays[r], opt);
      } catch (const std::exception& e) {
        o.failure = e.what();
        o.finite = false;
      }
      ev.methods.push_back(std::move(o));
    }
    out.rays.push_back(std::move(ev));
  }
  return out;
}

}  // namespace rayint
