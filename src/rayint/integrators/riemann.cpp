// riemann.cpp -- Riemann-sum compositing (Max 1995, "simplest numerical approximation ... Riemann
// sum"; back-to-front and front-to-back compositing) of the ray integral, Williams & Max Eq. 4.
//
// Samples. Either n equal sub-steps per segment (param n, default 64; breakpoints inside a
// segment are ignored, as a renderer does), or a fixed step dt along the whole ray (param dt),
// laid out from the eye: step k covers distance [k dt, (k+1) dt] from the eye and the last, far
// step is shortened to end at the far end; a step may straddle segment boundaries. Each step of
// length h is sampled once, at its midpoint: the scalar there (linear along the segment that
// holds the midpoint) gives rho and kappa through the transfer functions.
//
// Per sample (Williams & Max Eq. 6 with rho, kappa frozen at the midpoint; per channel):
//   colour = kappa * alpha (opacity-weighted, "associated" colour),  transparency = 1 - alpha,
// with the opacity alpha by param correction:
//   exp (default, no ref_dt): alpha = 1 - exp(-rho h), transparency exp(-rho h) (the smaller of
//                     the two by expm1 or exp, the other as 1 minus it: ~1 ulp, one call);
//   exp with ref_dt:  the opacity is tabulated for the reference step,
//                       alpha_ref = 1 - exp(-rho ref_dt),
//                     and corrected to the actual step,
//                       alpha = 1 - (1 - alpha_ref)^(h/ref_dt),
//                     evaluated through (h/ref_dt) log1p(-alpha_ref); up to rounding the same as
//                     exp, it shows that the correction restores convergence;
//   none with ref_dt: alpha = alpha_ref used unchanged for the actual step (the classic renderer
//                     bug: right only when h == ref_dt; as h -> 0 the ray turns opaque);
//   linear:           alpha = min(1, rho h) (Eq. 8 per sample, the textbook first-order sum).
// Compositing, param order:
//   btf (default): I = background; for samples far -> near: I = kappa alpha + (1 - alpha) I;
//   ftb:           C = 0, T = 1; for samples near -> far: C += T kappa alpha, T *= 1 - alpha;
//                  finally C += T background. No early ray termination, so ftb and btf sum the same
//                  terms and differ by rounding only (measured <= 4.9e-15 relative, 2560 samples).
// Transmittance: the product of the per-sample transparencies.
// Budget: a ray that needs more than kRiemannSampleBudget samples is refused
// (std::runtime_error) before any work is done.
// Diagnostics: stat "samples".
//
// Orders, measured on the smooth ray of tests/test_methods.cpp (no breakpoint inside a segment):
//   exp / corrected: 2 -- midpoint rule, per-step error O(h^3); fitted 1.997..2.000 for n = 8..64
//                    (n = 64 per segment, 256 samples: 7.1e-6 relative);
//   dt mode:         2 -- least-squares slope 1.99 over dt = 1/8..1/2048 (steps straddling the
//                    kinks at segment joins make the per-halving order zig-zag 1.3..2.7);
//   linear:          1 -- alpha = rho h misses rho^2 h^2/2 per step; fitted 1.00..1.02;
//   none:            0 -- right at h == ref_dt (bitwise the exp sum), worse as h shrinks.
// Kinks (breakpoints inside a segment) leave the midpoint rule second order; a jump in the scalar
// between segments makes it first order.
#include "rayint/integrators/riemann.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/integrators/factories.hpp"

namespace rayint {
namespace {

// Opacity and transparency of one sample of one channel (see the file comment).
using SampleOptics = StepOpacity;

inline SampleOptics sample_optics(const RiemannOptions& opt, double rho, double h) {
  switch (opt.opacity) {
    case OpacityRule::exact:
      return step_opacity(rho * h);
    case OpacityRule::corrected: {
      const double alpha_ref = -std::expm1(-rho * opt.ref_dt);  // the table entry
      return step_opacity(-(h / opt.ref_dt) * std::log1p(-alpha_ref));
    }
    case OpacityRule::none:
      return step_opacity(rho * opt.ref_dt);
    case OpacityRule::linear: {
      const double alpha = std::min(1.0, rho * h);
      return {alpha, 1.0 - alpha};
    }
  }
  return {0.0, 1.0};
}

// The quadratic coefficient of segment i (model/ray.hpp, Ray::quadratic; 0 for a linear ray).
double quadratic_at(const Ray& ray, std::size_t i) { return i < ray.quadratic.size() ? ray.quadratic[i] : 0.0; }

// Calls visit(scalar, h) for every sample of the ray, far -> near or near -> far; on a quadratic
// segment the scalar is the chord's quadratic at the sample (as a renderer samples the field).
template <class Visit>
void for_each_sample(const Ray& ray, const RiemannOptions& opt, bool far_to_near, Visit&& visit) {
  const std::size_t m = ray.segments.size();
  if (opt.dt <= 0.0) {
    const int n = opt.n;
    double samples = 0.0;
    for (const Segment& seg : ray.segments)
      if (seg.length > 0.0) samples += n;
    if (!(samples <= kRiemannSampleBudget))
      throw std::runtime_error(
          "riemann: n=" + std::to_string(n) + " needs " + std::to_string(samples) +
          " samples on this ray, over the budget of " + std::to_string(kRiemannSampleBudget));
    for (std::size_t idx = 0; idx < m; ++idx) {
      const std::size_t i = far_to_near ? idx : m - 1 - idx;
      const Segment& seg = ray.segments[i];
      if (!(seg.length > 0.0)) continue;
      const double h = seg.length / n;
      const double ds = seg.scalar_exit - seg.scalar_far;
      const double q = quadratic_at(ray, i);  // 0 on a linear segment: the same samples bit for bit
      for (int j = 0; j < n; ++j) {
        const int k = far_to_near ? j : n - 1 - j;
        const double s = (k + 0.5) * h;  // from the far end
        visit(seg.scalar_far + ((k + 0.5) / n) * ds + q * s * (s - seg.length), h);
      }
    }
    return;
  }
  // dt mode. exit_offset[i] = distance from the eye to the exit end of segment i, accumulated
  // once so that both directions see identical sample positions.
  thread_local std::vector<double> exit_offset;
  exit_offset.resize(m);
  double total = 0.0;
  for (std::size_t i = m; i-- > 0;) {
    exit_offset[i] = total;
    total += std::max(0.0, ray.segments[i].length);
  }
  if (!(total > 0.0)) return;
  const double steps = std::ceil(total / opt.dt);
  if (!(steps <= kRiemannSampleBudget))
    throw std::runtime_error("riemann: dt=" + std::to_string(opt.dt) + " needs " +
                             std::to_string(steps) + " samples on this ray, over the budget of " +
                             std::to_string(kRiemannSampleBudget));
  const long count = static_cast<long>(steps);
  // Segment i holds distances [exit_offset[i], exit_offset[i] + length_i) from the eye.
  auto far_end = [&](std::size_t j) {
    return exit_offset[j] + std::max(0.0, ray.segments[j].length);
  };
  std::size_t i = far_to_near ? 0 : m - 1;
  for (long step = 0; step < count; ++step) {
    const long k = far_to_near ? count - 1 - step : step;  // k counts from the eye
    const double lo = static_cast<double>(k) * opt.dt;
    const double hi = std::min(static_cast<double>(k + 1) * opt.dt, total);
    if (!(hi > lo)) continue;
    const double mid = 0.5 * (lo + hi);
    if (far_to_near) {
      while (i + 1 < m && mid < exit_offset[i]) ++i;
    } else {
      while (i > 0 && mid >= far_end(i)) --i;
    }
    const Segment& seg = ray.segments[i];
    const double u = seg.length > 0.0 ? (mid - exit_offset[i]) / seg.length : 0.0;  // from exit end
    const double from_exit = mid - exit_offset[i];
    const double bow = quadratic_at(ray, i) * from_exit * (from_exit - seg.length);  // s (s - L), symmetric
    visit(seg.scalar_exit + u * (seg.scalar_far - seg.scalar_exit) + bow, hi - lo);
  }
}


}  // namespace

RiemannOptions riemann_options(const MethodSpec& spec) {
  RiemannOptions o;
  const std::string where = "method " + spec.name + ": ";
  if (spec.params.count("n") && spec.params.count("dt"))
    throw std::invalid_argument(where + "give n (samples per segment) or dt (step), not both");
  // Types and ranges: the method table (registry.cpp); here only what combines parameters.
  o.n = spec.integer("n");
  o.dt = spec.has("dt") ? spec.number("dt") : 0.0;
  o.order = choice_of(spec, "order", {"btf", "ftb"}) == 0 ? CompositingOrder::back_to_front
                                                          : CompositingOrder::front_to_back;
  const std::size_t correction = choice_of(spec, "correction", {"exp", "none", "linear"});
  const bool has_ref = spec.has("ref_dt");
  o.ref_dt = has_ref ? spec.number("ref_dt") : 0.0;
  if (correction == 0) {  // exp
    o.opacity = has_ref ? OpacityRule::corrected : OpacityRule::exact;
  } else if (correction == 1) {  // none
    if (!has_ref)
      throw std::invalid_argument(where +
                                  "correction=none needs ref_dt (the step the opacity "
                                  "was tabulated for)");
    o.opacity = OpacityRule::none;
  } else {  // linear
    if (has_ref) throw std::invalid_argument(where + "correction=linear takes no ref_dt");
    o.opacity = OpacityRule::linear;
  }
  return o;
}

RiemannIntegrator::RiemannIntegrator(const TransferFunctions& tf, const RiemannOptions& options)
    : SamplingIntegrator(tf), opt_(options) {}

RayResult RiemannIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  RayResult r;
  long samples = 0;
  auto optics_at = [&](double scalar, double h, Rgb& colour, Rgb& transparency) {
    for (int c = 0; c < kChannels; ++c) {
      const SampleOptics o = sample_optics(opt_, tf_.density[c](scalar), h);
      colour[c] = tf_.color[c](scalar) * o.alpha;
      transparency[c] = o.transparency;
    }
    ++samples;
  };
  Rgb colour{}, transparency{};
  if (opt_.order == CompositingOrder::back_to_front) {
    r.intensity = ray.background;
    r.transmittance = {1.0, 1.0, 1.0};
    for_each_sample(ray, opt_, true, [&](double scalar, double h) {
      optics_at(scalar, h, colour, transparency);
      for (int c = 0; c < kChannels; ++c) {
        r.intensity[c] = colour[c] + transparency[c] * r.intensity[c];
        r.transmittance[c] *= transparency[c];
      }
    });
  } else {
    r.intensity = {0.0, 0.0, 0.0};
    r.transmittance = {1.0, 1.0, 1.0};  // accumulated from the eye
    for_each_sample(ray, opt_, false, [&](double scalar, double h) {
      optics_at(scalar, h, colour, transparency);
      for (int c = 0; c < kChannels; ++c) {
        r.intensity[c] += r.transmittance[c] * colour[c];
        r.transmittance[c] *= transparency[c];
      }
    });
    for (int c = 0; c < kChannels; ++c) r.intensity[c] += r.transmittance[c] * ray.background[c];
  }
  if (diag) diag->add_stat("samples", static_cast<double>(samples));
  return r;
}

std::unique_ptr<RayIntegrator> make_riemann(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<RiemannIntegrator>(tf, riemann_options(spec));
}

}  // namespace rayint
