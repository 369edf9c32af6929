// check.cpp -- a candidate renderer's intensities against the exact ray integral
// (Williams & Max 1992, Eq. 4; the `exact` method, integrators/exact.hpp), per ray and channel:
//   pass  <=>  |got - expected| <= max(abs_tol, rel_tol * |expected|).
// `expected` is accurate to ~1e-13 relative (tests/test_exact.cpp, Tolerances::exact_rel); the
// 50-digit reference (reference/reference.hpp) is computed alongside, when asked, only to report
// that uncertainty: the rule never uses it, so the verdict does not depend on its cost.
#include "rayint/studies/check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rayint/metrics/error_metrics.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/mesh/quadratic_methods.hpp"

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

CheckResult check_candidate(const Case& c, const Candidate& candidate, const CheckOptions& opt) {
  if (candidate.intensity.size() != c.rays.size())
    throw std::invalid_argument("check_candidate: the candidate has " +
                                std::to_string(candidate.intensity.size()) + " rays, the case " +
                                std::to_string(c.rays.size()));
  if (!valid_tolerance(opt.rel_tol) || !valid_tolerance(opt.abs_tol))
    throw std::invalid_argument("check_candidate: tolerances must be finite and >= 0");

  CheckResult out;
  out.case_name = c.name;
  out.case_source = c.source;
  out.candidate_source = candidate.source;
  out.renderer = candidate.renderer;
  out.options = opt;

  // The exact method; on quadratic chords (tet10) its polynomial path (mesh/quadratic_methods.hpp).
  const std::unique_ptr<RayIntegrator> exact = make_case_integrator(parse_method_spec("exact"), c.transfer);
  std::vector<ReferenceRay> refs;
  if (opt.with_reference) refs = reference_rays(c, opt.threads);

  CheckSummary& s = out.summary;
  s.rays = c.rays.size();
  double worst_excess = -1.0;
  if (opt.with_reference) s.expected_max_rel_uncertainty = 0.0;
  for (std::size_t r = 0; r < c.rays.size(); ++r) {
    const RayResult e = exact->integrate(c.rays[r], nullptr);
    RayCheck rc;
    rc.pass = true;
    for (int k = 0; k < kChannels; ++k) {
      ChannelCheck& ch = rc.channel[k];
      ch.expected = e.intensity[k];
      ch.got = candidate.intensity[r][k];
      ch.abs_error = std::isfinite(ch.got) && std::isfinite(ch.expected)
                         ? std::fabs(ch.got - ch.expected)
                         : INFINITY;
      ch.rel_error = relative_error(ch.got, ch.expected);
      ch.allowed = std::max(opt.abs_tol, opt.rel_tol * std::fabs(ch.expected));
      ch.pass = within_tolerance(ch.got, ch.expected, opt.rel_tol, opt.abs_tol);
      if (opt.with_reference) {
        ch.reference = refs[r].intensity[k].hi;
        ch.expected_error = absolute_error(ch.expected, refs[r].intensity[k]);
        const double u = relative_error(ch.expected, refs[r].intensity[k]);
        s.expected_max_rel_uncertainty = std::max(s.expected_max_rel_uncertainty, u);
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
    out.rays.push_back(rc);
  }
  out.pass = s.failed_channels == 0;
  return out;
}

}  // namespace rayint
