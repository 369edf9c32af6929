#include "rayint/studies/grad_study.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/preintegrated.hpp"
#include "rayint/integrators/psi_table_grad.hpp"
#include "rayint/integrators/riemann_grad.hpp"

namespace rayint {

bool has_gradient(const MethodSpec& spec) {
  return spec.name == "exact" || spec.name == "riemann" || spec.name == "nerf" || spec.name == "pl_nerf" ||
         spec.name == "psi_table" || spec.name == "preintegrated";
}

namespace {

using GradientFunction = std::function<RayGradient(const Ray&)>;

// The gradient of `spec` for rays of one case (a table method builds its table once here).
GradientFunction gradient_function(const MethodSpec& spec, const TransferFunctions& tf) {
  if (spec.name == "exact") {
    for (const auto& [key, value] : spec.params)
      if (key != "path")
        throw std::invalid_argument("method " + spec.label() + ": unknown parameter " + key);
    return [g = ExactRayGradient(tf)](const Ray& ray) { return g(ray); };
  }
  if (spec.name == "riemann")
    return [&tf, o = riemann_options(spec)](const Ray& ray) { return riemann_ray_gradient(tf, ray, o); };
  if (spec.name == "nerf")
    return [&tf, o = nerf_options(spec)](const Ray& ray) { return nerf_ray_gradient(tf, ray, o, false); };
  if (spec.name == "pl_nerf")
    return [&tf, o = pl_nerf_options(spec)](const Ray& ray) { return nerf_ray_gradient(tf, ray, o, true); };
  if (spec.name == "psi_table")
    return [&tf, size = spec.integer("size"), lookup = table::parse_lookup(spec)](const Ray& ray) {
      return psi_table_ray_gradient(tf, ray, size, lookup);
    };
  if (spec.name == "preintegrated") {
    auto table = std::make_shared<const PreintegratedIntegrator>(tf, preintegrated_options(spec));
    return [&tf, table](const Ray& ray) { return table->gradient(tf, ray); };
  }
  throw std::invalid_argument(
      "method " + spec.label() +
      ": no gradient (gradients exist for exact, riemann, nerf, pl_nerf, psi_table and preintegrated)");
}

}  // namespace

RayGradient method_gradient(const MethodSpec& spec, const TransferFunctions& tf, const Ray& ray) {
  return gradient_function(spec, tf)(ray);
}

double gradient_relative_error(const RayGradient& got, const RayGradient& want, int c) {
  std::vector<double> w;
  want.for_each(c, [&w](double v, const char*, std::size_t, const char*) { w.push_back(v); });
  std::vector<double> g;
  got.for_each(c, [&g](double v, const char*, std::size_t, const char*) { g.push_back(v); });
  if (g.size() != w.size()) return std::nan("");
  double scale = want.channel_scale(c);
  if (std::isnan(scale)) return scale;
  if (scale == 0.0) scale = 1.0;
  double worst = 0.0;
  const bool skip_undefined = !want.undefined.empty();
  for (std::size_t i = 0; i < g.size(); ++i) {
    // An entry `want` says does not exist: `got` must say so too (NaN), else the error is NaN.
    if (skip_undefined && std::isnan(w[i])) {
      if (std::isnan(g[i])) continue;
      return std::nan("");
    }
    const double e = std::fabs(g[i] - w[i]) / scale;
    if (std::isnan(e)) return e;
    worst = std::max(worst, e);
  }
  return worst;
}

GradCaseResult grad_case(const Case& c, const GradStudyOptions& options) {
  GradCaseResult out;
  out.name = c.name;
  out.source = c.source;
  std::vector<MethodSpec> methods = options.methods;
  if (methods.empty()) methods.push_back(parse_method_spec("exact"));
  // One gradient function per method for the whole case (or why it has none).
  std::vector<GradientFunction> functions(methods.size());
  std::vector<std::string> setup_error(methods.size());
  for (std::size_t k = 0; k < methods.size(); ++k) {
    try {
      functions[k] = gradient_function(methods[k], c.transfer);
    } catch (const std::exception& e) {
      setup_error[k] = e.what();
    }
  }
  const ExactRayGradient exact(c.transfer);
  for (const Ray& ray : c.rays) {
    GradRayResult r;
    r.exact = exact(ray);
    if (options.reference) {
      ReferenceGradientOptions ro;
      ro.threads = options.threads;
      r.reference = reference_gradient(c.transfer, ray, ro);
    }
    for (std::size_t k = 0; k < methods.size(); ++k) {
      const MethodSpec& spec = methods[k];
      GradMethodResult m;
      m.label = spec.label();
      try {
        if (!functions[k]) throw std::invalid_argument(setup_error[k]);
        m.gradient = spec.name == "exact" && spec.params.empty() ? r.exact : functions[k](ray);
        m.ok = true;
      } catch (const std::exception& e) {
        m.error = e.what();
      }
      if (m.ok) {
        for (int ch = 0; ch < kChannels; ++ch) {
          m.error_vs_exact[ch] = gradient_relative_error(m.gradient, r.exact, ch);
          if (r.reference) {
            const RayGradient& ref = r.reference->gradient;
            m.error_vs_reference[ch] = gradient_relative_error(m.gradient, ref, ch);
            const double I = ref.intensity[ch];
            const double d = std::fabs(m.gradient.intensity[ch] - I);
            m.intensity_error[ch] = I != 0.0 ? d / std::fabs(I) : d;
          } else {
            m.error_vs_reference[ch] = std::nan("");
            m.intensity_error[ch] = std::nan("");
          }
        }
      }
      r.methods.push_back(std::move(m));
    }
    out.rays.push_back(std::move(r));
  }
  return out;
}

GradCheckResult grad_check(const Case& c, const GradCandidate& candidate, const GradCheckOptions& options) {
  const double rel_tol = options.rel_tol, abs_tol = options.abs_tol;
  const bool against_reference = options.against == GradCheckAgainst::reference;
  GradCheckResult res;
  res.case_name = c.name;
  res.renderer = candidate.renderer;
  res.against = options.against;
  res.rel_tol = rel_tol;
  res.abs_tol = abs_tol;
  if (against_reference) res.exact_vs_reference = Rgb{};
  const ExactRayGradient exact_gradient(c.transfer);
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    RayGradient exact = exact_gradient(c.rays[i]);
    if (against_reference) {
      ReferenceGradientOptions ro;
      ro.threads = options.threads;
      RayGradient reference = reference_gradient(c.transfer, c.rays[i], ro).gradient;
      for (int ch = 0; ch < kChannels; ++ch)
        res.exact_vs_reference[ch] =
            std::max(res.exact_vs_reference[ch], gradient_relative_error(exact, reference, ch));
      // Which entries do not exist is decided from the inputs alike by both (at a jump).
      if (reference.undefined.empty()) reference.undefined = exact.undefined;
      exact = std::move(reference);
    }
    const RayGradient& got = candidate.rays.at(i);
    Rgb scale{};
    for (int ch = 0; ch < kChannels; ++ch) {
      scale[ch] = exact.channel_scale(ch);
      const double allowed = std::max(abs_tol, rel_tol * scale[ch]);
      std::vector<double> g;
      got.for_each(ch, [&g](double v, const char*, std::size_t, const char*) { g.push_back(v); });
      std::size_t k = 0;
      exact.for_each(ch, [&](double want, const char* block, std::size_t index, const char* param) {
        const double have = g.at(k++);
        if (std::isnan(want) && !exact.undefined.empty()) {  // no derivative here: nothing to check
          ++res.undefined;
          return;
        }
        if (std::isnan(have)) {  // null in the candidate: it cannot give this entry -- not a pass
          ++res.entries;
          ++res.failed;
          if (res.null_in_candidate++ == 0)
            res.first_null = GradCheckEntry{i, ch, block, index, param, have, want, allowed, std::nan("")};
          return;
        }
        const double diff = std::fabs(have - want);
        const double excess = allowed > 0.0 ? diff / allowed : (diff == 0.0 ? 0.0 : HUGE_VAL);
        const bool fail = !(diff <= allowed);
        ++res.entries;
        if (fail) ++res.failed;
        const bool worse = !res.worst || (std::isnan(excess) && !std::isnan(res.worst->excess)) ||
                           (!std::isnan(res.worst->excess) && excess > res.worst->excess);
        if (worse) {
          res.worst = GradCheckEntry{i, ch, block, index, param, have, want, allowed,
                                     std::isfinite(have) ? excess : std::nan("")};
        }
      });
    }
    res.channel_scale.push_back(scale);
    if (res.undefined_reason.empty() && !exact.undefined.empty())
      res.undefined_reason = "ray " + std::to_string(i) + ": " + exact.undefined;
  }
  return res;
}

}  // namespace rayint
