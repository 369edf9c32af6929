// check.cpp -- a candidate renderer's intensities against the exact ray integral
// (Williams & Max 1992, Eq. 4; the `exact` method, integrators/exact.hpp), per ray and channel:
//   pass  <=>  |got - expected| <= max(abs_tol, rel_tol * |expected|).
// `expected` is accurate to ~1e-13 relative (tests/test_exact.cpp, Tolerances::exact_rel); the
// 50-digit reference (reference/reference.hpp) is computed alongside, when asked, only to report
// that uncertainty: the rule never uses it, so the verdict does not depend on its cost.
// Mesh cases of cells other than tetrahedra (check_candidate_own): `expected` is the cells' own
// interpolation integrated in double and the reference the 50-digit cell reference, both from
// evaluate_own_cells (studies/own_cells_eval.hpp), the same rule on the same per-ray diff.
#include "rayint/studies/check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rayint/metrics/error_metrics.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/quadratic_methods.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace rayint {
namespace {

bool valid_tolerance(double t) { return std::isfinite(t) && t >= 0.0; }

// How far past its allowance a channel is: abs_error / allowed (0/0 = 0, x/0 = inf, NaN = inf).
double excess(const ChannelCheck& ch) {
  if (!(ch.abs_error >= 0.0)) return INFINITY;
  if (ch.abs_error == 0.0) return 0.0;
  return ch.allowed > 0.0 ? ch.abs_error / ch.allowed : INFINITY;
}

}  // namespace

bool within_tolerance(double got, double expected, double rel_tol, double abs_tol) {
  if (!std::isfinite(got) || !std::isfinite(expected)) return false;
  return std::fabs(got - expected) <= std::max(abs_tol, rel_tol * std::fabs(expected));
}

namespace {

void require_preconditions(std::size_t candidate_rays, std::size_t case_rays, const CheckOptions& opt) {
  if (candidate_rays != case_rays)
    throw std::invalid_argument("check_candidate: the candidate has " + std::to_string(candidate_rays) +
                                " rays, the case " + std::to_string(case_rays));
  if (!valid_tolerance(opt.rel_tol) || !valid_tolerance(opt.abs_tol))
    throw std::invalid_argument("check_candidate: tolerances must be finite and >= 0");
}

CheckResult result_header(const std::string& name, const std::string& source, const Candidate& candidate,
                          const CheckOptions& opt) {
  CheckResult out;
  out.case_name = name;
  out.case_source = source;
  out.candidate_source = candidate.source;
  out.renderer = candidate.renderer;
  out.options = opt;
  out.summary.rays = candidate.intensity.size();
  if (opt.with_reference) out.summary.expected_max_rel_uncertainty = 0.0;
  return out;
}

// The pass rule on ray r, whose expected intensity is `expected` (NaN channels: it failed) and
// whose reference context `reference(k, ch)` fills in (it returns the channel's relative
// uncertainty, NaN when unknown); appends the ray and updates the summary.
template <class Reference>
void check_ray(CheckResult& out, const Candidate& candidate, std::size_t r, const Rgb& expected,
               double& worst_excess, Reference&& reference) {
  const CheckOptions& opt = out.options;
  CheckSummary& s = out.summary;
  RayCheck rc;
  rc.pass = true;
  for (int k = 0; k < kChannels; ++k) {
    ChannelCheck& ch = rc.channel[k];
    ch.expected = expected[k];
    ch.got = candidate.intensity[r][k];
    ch.abs_error = std::isfinite(ch.got) && std::isfinite(ch.expected) ? std::fabs(ch.got - ch.expected) : INFINITY;
    ch.rel_error = relative_error(ch.got, ch.expected);
    ch.allowed = std::max(opt.abs_tol, opt.rel_tol * std::fabs(ch.expected));
    ch.pass = within_tolerance(ch.got, ch.expected, opt.rel_tol, opt.abs_tol);
    if (opt.with_reference) {
      const double u = reference(k, ch);
      if (!std::isnan(u)) s.expected_max_rel_uncertainty = std::max(s.expected_max_rel_uncertainty, u);
    }
    ++s.channels;
    if (!ch.pass) ++s.failed_channels;
    rc.pass = rc.pass && ch.pass;
    s.max_abs_error = std::max(s.max_abs_error, ch.abs_error);
    s.max_rel_error = std::max(s.max_rel_error, ch.rel_error);
    if (const double x = excess(ch); x > worst_excess) {
      worst_excess = x;
      s.worst_ray = r;
      s.worst_channel = k;
    }
  }
  if (!rc.pass) ++s.failed_rays;
  out.rays.push_back(std::move(rc));
}

}  // namespace

CheckResult check_candidate(const Case& c, const Candidate& candidate, const CheckOptions& opt) {
  require_preconditions(candidate.intensity.size(), c.rays.size(), opt);
  CheckResult out = result_header(c.name, c.source, candidate, opt);
  // The exact method; on quadratic chords (tet10) its polynomial path (mesh/quadratic_methods.hpp).
  const std::unique_ptr<RayIntegrator> exact = make_case_integrator(parse_method_spec("exact"), c.transfer);
  std::vector<ReferenceRay> refs;
  if (opt.with_reference) refs = reference_rays(c, opt.threads);
  double worst_excess = -1.0;
  for (std::size_t r = 0; r < c.rays.size(); ++r) {
    const RayResult e = exact->integrate(c.rays[r], nullptr);
    check_ray(out, candidate, r, e.intensity, worst_excess, [&](int k, ChannelCheck& ch) {
      ch.reference = refs[r].intensity[k].hi;
      ch.expected_error = absolute_error(ch.expected, refs[r].intensity[k]);
      return relative_error(ch.expected, refs[r].intensity[k]);
    });
  }
  out.pass = out.summary.failed_channels == 0;
  return out;
}

CheckResult check_candidate_own(const MeshCase& mc, const Candidate& candidate, const CheckOptions& opt) {
  if (!mc.cells) throw std::invalid_argument(mc.source + ": not a mesh case of cells in their own interpolation");
  require_preconditions(candidate.intensity.size(), evaluation_rays(mc).size(), opt);
  CheckResult out = result_header(mc.name, mc.source, candidate, opt);
  out.expected_method = "own";
  const OwnCaseEvaluation own = evaluate_own_cells(mc, opt.with_reference, opt.threads);
  if (own.rays.size() != candidate.intensity.size())  // evaluate_own_cells traces evaluation_rays(mc)
    throw std::logic_error("check_candidate_own: evaluate_own_cells gave " + std::to_string(own.rays.size()) + " rays");
  double worst_excess = -1.0;
  for (std::size_t r = 0; r < own.rays.size(); ++r) {
    const OwnRayEvaluation& e = own.rays[r];
    // A chord that did not converge: no expected value, so every channel fails (never a pass).
    const Rgb expected = e.converged ? e.intensity : Rgb{NAN, NAN, NAN};
    check_ray(out, candidate, r, expected, worst_excess, [&](int k, ChannelCheck& ch) {
      if (!e.referenced) return static_cast<double>(NAN);
      ch.reference = e.reference_intensity[k];
      ch.expected_error = std::isfinite(ch.expected) ? std::fabs(ch.expected - ch.reference) : NAN;
      return std::isfinite(ch.expected) ? relative_error(ch.expected, ch.reference) : static_cast<double>(NAN);
    });
    RayCheck& rc = out.rays.back();
    if (!e.converged) {
      rc.expected_failure = e.failure.empty() ? "the own-interpolation integral did not converge" : e.failure;
      ++out.summary.expected_failed_rays;
    }
    if (opt.with_reference && !e.referenced) {
      rc.reference_failure = e.reference_failure.empty() ? "the 50-digit reference failed" : e.reference_failure;
      ++out.summary.reference_failed_rays;
    }
  }
  out.pass = out.summary.failed_channels == 0 && out.summary.expected_failed_rays == 0;
  return out;
}

}  // namespace rayint
