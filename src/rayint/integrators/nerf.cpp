// nerf.cpp -- the quadratures of NeRF-style renderers, as methods on a case's rays and on
// explicit samples (nerf.hpp has the formulas).
//
// nerf (Mildenhall et al. 2020, NeRF, Eq. 3; Max 1995 for the alpha compositing):
//   C = sum_i T_i (1 - exp(-sigma_i delta_i)) c_i + T_N * background,
//   T_i = prod_{j<i} exp(-sigma_j delta_j),
// the exact integral of a density and colour that are constant on each interval. On a case's
// rays each segment is cut into n equal intervals (param n, default 64) and sampled, through the
// transfer functions, at the scalar of one point per interval (param at):
//   at=mid (default)  the interval's midpoint: nerfstudio's sample is the centre of its bin,
//                     Frustums.get_positions() = (starts + ends) / 2, with delta = ends - starts
//                     (nerfstudio/cameras/rays.py, RaySamples.get_weights);
//   at=near           the interval's eye-side end: NeRF 2020 (bmild/nerf run_nerf.py, raw2outputs)
//                     samples t_i = linspace(near, far, N) and gives sample i the distance to the
//                     next one, delta_i = t_{i+1} - t_i.
// The last interval, which the implementations treat differently:
//   last=interval (default)  the farthest sample's interval ends at the far end of the ray, where
//                     the background enters with the remaining T (nerfstudio: delta = the last
//                     bin's width, background blended with 1 - sum of weights; instant-ngp-style
//                     CUDA marchers: each sample carries its own march step dt and the background
//                     is added with the remaining T);
//   last=inf          NeRF 2020: one more sample at the far end of the ray with delta = 1e10
//                     (kNerfLastDelta; "the 'distance' from the last integration time is
//                     infinity"), so wherever the density there is > 0 that sample is opaque and
//                     hides the background. PL-NeRF's code (run_plnerf.py) keeps the same idea:
//                     it pads the ray with density 0 at `near` and 1e10 at `far`, a far wall.
// Front-to-back from the eye, no early ray termination (instant-ngp stops at T < 1e-4).
//
// pl_nerf (Uy et al. 2023, "NeRF Revisited", Sec. 4, the piecewise-linear density; their
// run_plnerf.py compute_weights_piecewise_linear): samples at the n + 1 ends of the n equal
// intervals of each segment; on each interval the density is the linear interpolant of its two
// samples, whose transmittance is exact, exp(-(sigma_i + sigma_{i+1}) delta_i / 2); the colour is
// the mean of the two samples (param color=mid, their color_mode "midpoint": the linear
// interpolant's colour at the interval's midpoint) or the eye-side sample (color=near, their
// "left"). Where the transfer functions are linear over an interval (no breakpoint inside) and
// kappa is constant, the interval is integrated exactly; tests/test_nerf.cpp checks that against
// the 50-digit reference (<= 1e-14), and the orders below.
//
// On an interval where the transfer functions are linear (no breakpoint inside), rho(mid) h is the
// trapezoid (rho_0 + rho_1) h / 2 and kappa(mid) the mean of the ends: nerf at=mid and pl_nerf are
// then the same sum, and differ only on intervals with a breakpoint inside (tested, [nerf]).
// Orders on a smooth ray (tests/test_nerf.cpp, [nerf]), measured from n to 2n, n = 8..64:
// nerf at=mid 1.9993..2.0000 (the midpoint rule), at=near 0.945..0.986; pl_nerf 1.9993..2.0000
// (color=mid), 1.0009..1.0034 (color=near). pl_nerf on linear rho with constant kappa: <= 9.1e-16
// relative against the 50-digit reference.
// Budget: a ray needing more than kRiemannSampleBudget samples is refused (std::runtime_error).
// Diagnostics: stat "samples".
#include "rayint/integrators/nerf.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/integrators/factories.hpp"

namespace rayint {
namespace {


}  // namespace

CompositeResult nerf_composite(const double* sigma, const double* colour, const double* delta,
                               std::size_t count) {
  FrontToBack acc;
  for (std::size_t i = 0; i < count; ++i) acc.add(sigma[i] * delta[i], colour[i]);
  return {acc.emission, acc.transmittance};
}

CompositeResult pl_nerf_composite(const double* sigma, const double* colour, const double* delta,
                                  std::size_t intervals, bool mid_colour) {
  FrontToBack acc;
  for (std::size_t i = 0; i < intervals; ++i)
    acc.add(0.5 * (sigma[i] + sigma[i + 1]) * delta[i],
            mid_colour ? 0.5 * (colour[i] + colour[i + 1]) : colour[i]);
  return {acc.emission, acc.transmittance};
}

NerfOptions nerf_options(const MethodSpec& spec) {
  NerfOptions o;
  o.n = spec.integer("n");  // ranges and choices: the method table (registry.cpp)
  o.at = choice_of(spec, "at", {"mid", "near"}) == 0 ? NerfSampleAt::mid : NerfSampleAt::near;
  o.last_inf = choice_of(spec, "last", {"interval", "inf"}) == 1;
  return o;
}

NerfOptions pl_nerf_options(const MethodSpec& spec) {
  NerfOptions o;
  o.n = spec.integer("n");
  o.mid_colour = choice_of(spec, "color", {"mid", "near"}) == 0;
  return o;
}

NerfIntegrator::NerfIntegrator(const TransferFunctions& tf, const NerfOptions& options,
                               bool piecewise_linear)
    : SamplingIntegrator(tf), opt_(options), linear_(piecewise_linear) {}

RayResult NerfIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  const int n = opt_.n;
  double budget = 0.0;
  for (const Segment& seg : ray.segments)
    if (seg.length > 0.0) budget += linear_ ? n + 1.0 : n;
  if (!(budget <= kRiemannSampleBudget))
    throw std::runtime_error((linear_ ? "pl_nerf: n=" : "nerf: n=") + std::to_string(n) +
                             " needs " + std::to_string(budget) +
                             " samples on this ray, over the budget of " +
                             std::to_string(kRiemannSampleBudget));
  FrontToBack acc[kChannels];
  long samples = 0;
  bool any_length = false;
  for (std::size_t idx = ray.segments.size(); idx-- > 0;) {  // from the eye outward
    const Segment& seg = ray.segments[idx];
    if (!(seg.length > 0.0)) continue;
    any_length = true;
    const double h = seg.length / n;
    const double ds = seg.scalar_far - seg.scalar_exit;
    // The scalar k intervals from the segment's exit end (k = n is the far end, exactly); on a
    // quadratic chord (model/ray.hpp) plus q x (x - L), x = k h from the exit (q = 0: nothing).
    const double q = idx < ray.quadratic.size() ? ray.quadratic[idx] : 0.0;
    auto scalar_at = [&](double k) {
      const double x = k * h;
      return k == n ? seg.scalar_far : seg.scalar_exit + (k / n) * ds + q * x * (x - seg.length);
    };
    if (!linear_) {
      const double offset = opt_.at == NerfSampleAt::mid ? 0.5 : 0.0;
      for (int k = 0; k < n; ++k) {
        const double s = scalar_at(k + offset);
        for (int c = 0; c < kChannels; ++c) acc[c].add(tf_.density[c](s) * h, tf_.color[c](s));
      }
      samples += n;
      continue;
    }
    Rgb rho0{}, kappa0{};
    for (int c = 0; c < kChannels; ++c) {
      rho0[c] = tf_.density[c](seg.scalar_exit);
      kappa0[c] = tf_.color[c](seg.scalar_exit);
    }
    for (int k = 1; k <= n; ++k) {
      const double s = scalar_at(k);
      for (int c = 0; c < kChannels; ++c) {
        const double rho1 = tf_.density[c](s), kappa1 = tf_.color[c](s);
        acc[c].add(0.5 * (rho0[c] + rho1) * h,
                   opt_.mid_colour ? 0.5 * (kappa0[c] + kappa1) : kappa0[c]);
        rho0[c] = rho1;
        kappa0[c] = kappa1;
      }
    }
    samples += n + 1;
  }
  if (!linear_ && opt_.last_inf && any_length) {  // NeRF 2020's last sample, delta = 1e10
    const double s = ray.segments.front().scalar_far;
    for (int c = 0; c < kChannels; ++c)
      acc[c].add(tf_.density[c](s) * kNerfLastDelta, tf_.color[c](s));
    ++samples;
  }
  RayResult r;
  for (int c = 0; c < kChannels; ++c) {
    r.intensity[c] = acc[c].emission + acc[c].transmittance * ray.background[c];
    r.transmittance[c] = acc[c].transmittance;
  }
  if (diag) diag->add_stat("samples", static_cast<double>(samples));
  return r;
}

std::unique_ptr<RayIntegrator> make_nerf(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<NerfIntegrator>(tf, nerf_options(spec), false);
}

std::unique_ptr<RayIntegrator> make_pl_nerf(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<NerfIntegrator>(tf, pl_nerf_options(spec), true);
}

}  // namespace rayint
