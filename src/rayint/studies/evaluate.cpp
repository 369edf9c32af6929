#include "rayint/studies/evaluate.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "rayint/core/parallel.hpp"
#include "rayint/core/statistics.hpp"
#include "rayint/mesh/quadratic_methods.hpp"
#include "rayint/metrics/error_metrics.hpp"

namespace rayint {

void mark_failed(MethodOutcome& o, const std::string& why) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Rgb none{nan, nan, nan};
  o.failure = why.empty() ? std::string("failed") : why;
  o.finite = false;
  o.result = {none, none};
  o.abs_error = o.rel_error = o.ulp_error = o.transmittance_rel_error = none;
  o.seconds_per_ray = nan;
}

std::vector<MethodSummary> summarise_methods(const CaseEvaluation& c) {
  std::vector<MethodSummary> out;
  if (c.rays.empty()) return out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t m = 0; m < c.rays.front().methods.size(); ++m) {
    MethodSummary s;
    s.method = c.rays.front().methods[m].method;
    std::size_t ok = 0;
    double seconds = 0.0;
    for (std::size_t r = 0; r < c.rays.size(); ++r) {
      const MethodOutcome& o = c.rays[r].methods[m];
      ++s.rays;
      if (o.failed()) {
        if (s.failed++ == 0) s.first_failure = "ray " + std::to_string(r) + ": " + o.failure;
        continue;
      }
      ++ok;
      seconds += o.seconds_per_ray;
      for (int ch = 0; ch < kChannels; ++ch) {
        s.max_rel_error = std::max(s.max_rel_error, o.rel_error[ch]);
        s.max_ulp_error = std::max(s.max_ulp_error, o.ulp_error[ch]);
      }
    }
    if (ok == 0 || !c.with_reference) s.max_rel_error = s.max_ulp_error = nan;
    s.mean_seconds_per_ray = ok > 0 ? seconds / static_cast<double>(ok) : nan;
    out.push_back(std::move(s));
  }
  return out;
}

std::size_t failed_outcomes(const std::vector<CaseEvaluation>& cases) {
  std::size_t n = 0;
  for (const auto& c : cases)
    for (const auto& ray : c.rays)
      for (const auto& o : ray.methods) n += o.failed() ? 1 : 0;
  return n;
}

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
      integrators.push_back(make_case_integrator(spec, c.transfer));  // exact takes quadratic chords
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
        mark_failed(o, build_errors[m]);
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
        if (!o.finite) {
          // The ODE methods stop early and return NaN; their diagnostics say why.
          std::string why = "non-finite result (intensity or transmittance is NaN or infinite)";
          for (const char* stop : {"step_budget_exhausted", "step_size_collapsed"})
            if (o.diagnostics.branches.count(stop)) why = std::string("did not converge: ") + stop;
          mark_failed(o, why);
        } else if (opt.measure_time) {
          o.seconds_per_ray = time_per_ray(*integrators[m], c.rays[r], opt);
        }
      } catch (const std::exception& e) {
        mark_failed(o, e.what());
      }
      ev.methods.push_back(std::move(o));
    }
    out.rays.push_back(std::move(ev));
  }
  return out;
}

}  // namespace rayint
