#include "rayint/studies/grad_study.hpp"

#include <cmath>
#include <stdexcept>

#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/psi_table_grad.hpp"
#include "rayint/integrators/riemann_grad.hpp"

namespace rayint {

bool has_gradient(const MethodSpec& spec) {
  return spec.name == "exact" || spec.name == "riemann" || spec.name == "nerf" || spec.name == "pl_nerf" ||
         spec.name == "psi_table";
}

RayGradient method_gradient(const MethodSpec& spec, const TransferFunctions& tf, const Ray& ray) {
  if (spec.name == "exact") {
    for (const auto& [key, value] : spec.params)
      if (key != "path")
        throw std::invalid_argument("method " + spec.label() + ": unknown parameter " + key);
    return exact_ray_gradient(tf, ray);
  }
  if (spec.name == "riemann") return riemann_ray_gradient(tf, ray, riemann_options(spec));
  if (spec.name == "nerf") return nerf_ray_gradient(tf, ray, nerf_options(spec), false);
  if (spec.name == "pl_nerf") return nerf_ray_gradient(tf, ray, pl_nerf_options(spec), true);
  if (spec.name == "psi_table")
    return psi_table_ray_gradient(tf, ray, spec.integer("size"), table::parse_lookup(spec));
  throw std::invalid_argument("method " + spec.label() +
                              ": no gradient (gradients exist for exact, riemann, nerf, pl_nerf and psi_table)");
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
  for (std::size_t i = 0; i < g.size(); ++i) {
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
  for (const Ray& ray : c.rays) {
    GradRayResult r;
    r.exact = exact_ray_gradient(c.transfer, ray);
    if (options.reference) {
      ReferenceGradientOptions ro;
      ro.threads = options.threads;
      r.reference = reference_gradient(c.transfer, ray, ro);
    }
    for (const MethodSpec& spec : methods) {
      GradMethodResult m;
      m.label = spec.label();
      try {
        m.gradient = spec.name == "exact" && spec.params.empty() ? r.exact
                                                                 : method_gradient(spec, c.transfer, ray);
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

GradCheckResult grad_check(const Case& c, const GradCandidate& candidate, double rel_tol, double abs_tol) {
  GradCheckResult res;
  res.case_name = c.name;
  res.renderer = candidate.renderer;
  res.rel_tol = rel_tol;
  res.abs_tol = abs_tol;
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    const RayGradient exact = exact_ray_gradient(c.transfer, c.rays[i]);
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
  }
  return res;
}

}  // namespace rayint
