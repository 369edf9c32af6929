// Reverse-mode derivative of the sampled renderers' sums (see riemann_grad.hpp). The march is
// written once, as a list of steps far -> near, each with up to two samples; the forward pass
// composites back to front and keeps the light entering each step; the reverse pass hands the
// adjoint (the transparency of everything nearer the eye) to x, colour, h and the samples, and
// from there to the length, the end scalars and the transfer-function nodes.
#include "rayint/integrators/riemann_grad.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rayint {
namespace {

struct SamplePoint {
  double s = 0.0;       // scalar
  double d_far = 0.0;   // ds / d scalar_far
  double d_exit = 0.0;  // ds / d scalar_exit
  double w_rho = 0.0;   // weight in the step's density
  double w_kappa = 0.0; // weight in the step's colour
  double toward = 0.0;  // sign: the segment's interior lies at larger (> 0) or smaller scalars
};

// The interval node_weights differentiates f in at a sample: the one toward the segment's
// interior, so that a sample exactly on a node at a segment end is differentiated like that
// segment's pieces -- except on a jump of f, where the forward's lookup (PiecewiseLinear's
// operator()) returns the LEFT value, so the derivative is the left interval's (one-sided: the
// sum is left-continuous there; see riemann_grad.hpp). f_jumps: f.has_jump(), known to the
// caller (a function without a jump is not searched for one at every sample).
double interval_key(const PiecewiseLinear& f, bool f_jumps, const SamplePoint& sp) {
  return sp.toward < 0.0 || (f_jumps && jump_node(f, sp.s) != kNoJump) ? std::nextafter(sp.s, -HUGE_VAL) : sp.s;
}

struct Step {
  std::size_t segment = 0;
  double h = 0.0;
  double dh_dlength = 0.0;
  int count = 1;
  SamplePoint p[2];
};

RayGradient march_gradient(const TransferFunctions& tf, const Ray& ray, const std::vector<Step>& steps) {
  RayGradient g = RayGradient::zeros(tf, ray);
  const std::size_t n = steps.size();
  // Forward: per step and channel the optics and the light entering.
  std::vector<double> incoming(n * kChannels), alpha(n * kChannels), transparency(n * kChannels),
      colour(n * kChannels), rho_sum(n * kChannels);
  Rgb I = ray.background;
  for (std::size_t k = 0; k < n; ++k) {
    const Step& st = steps[k];
    for (int c = 0; c < kChannels; ++c) {
      double r = 0.0, kap = 0.0;
      for (int i = 0; i < st.count; ++i) {
        r += st.p[i].w_rho * tf.density[c](st.p[i].s);
        kap += st.p[i].w_kappa * tf.color[c](st.p[i].s);
      }
      const StepOpacity o = step_opacity(r * st.h);
      const std::size_t q = k * kChannels + static_cast<std::size_t>(c);
      incoming[q] = I[c];
      alpha[q] = o.alpha;
      transparency[q] = o.transparency;
      colour[q] = kap;
      rho_sum[q] = r;
      I[c] = kap * o.alpha + o.transparency * I[c];
    }
  }
  g.intensity = I;
  std::array<bool, kChannels> rho_jumps{}, kappa_jumps{};
  for (int c = 0; c < kChannels; ++c) {
    rho_jumps[c] = tf.density[c].has_jump();
    kappa_jumps[c] = tf.color[c].has_jump();
  }
  Rgb adjoint{1.0, 1.0, 1.0};
  for (std::size_t k = n; k-- > 0;) {
    const Step& st = steps[k];
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t q = k * kChannels + static_cast<std::size_t>(c);
      // I = colour (1 - tr) + tr I_in, tr = e^{-x}: dI/dx = tr (colour - I_in).
      const double x_bar = adjoint[c] * transparency[q] * (colour[q] - incoming[q]);
      const double colour_bar = adjoint[c] * alpha[q];
      g.length[st.segment][c] += x_bar * rho_sum[q] * st.dh_dlength;
      for (int i = 0; i < st.count; ++i) {
        const SamplePoint& sp = st.p[i];
        const double rho_bar = x_bar * st.h * sp.w_rho;
        const double kappa_bar = colour_bar * sp.w_kappa;
        const NodeWeights nr = node_weights(tf.density[c], interval_key(tf.density[c], rho_jumps[c], sp), sp.s);
        const NodeWeights nk = node_weights(tf.color[c], interval_key(tf.color[c], kappa_jumps[c], sp), sp.s);
        for (int j = 0; j < nr.count; ++j) {
          g.density[c][nr.node[j]].value += rho_bar * nr.w[j];
          g.density[c][nr.node[j]].position += rho_bar * nr.dp[j];
        }
        for (int j = 0; j < nk.count; ++j) {
          g.color[c][nk.node[j]].value += kappa_bar * nk.w[j];
          g.color[c][nk.node[j]].position += kappa_bar * nk.dp[j];
        }
        const double s_bar = rho_bar * nr.slope + kappa_bar * nk.slope;
        g.scalar_far[st.segment][c] += s_bar * sp.d_far;
        g.scalar_exit[st.segment][c] += s_bar * sp.d_exit;
      }
      adjoint[c] *= transparency[q];
    }
  }
  g.background = adjoint;
  // A jump's two position entries carry its derivative on the first (model/ray_gradient.hpp).
  tie_jump_positions(tf, g.density, g.color);
  return g;
}

}  // namespace

RayGradient riemann_ray_gradient(const TransferFunctions& tf, const Ray& ray, const RiemannOptions& opt) {
  if (opt.dt > 0.0 || opt.opacity != OpacityRule::exact)
    throw std::invalid_argument(
        "riemann gradient: only n samples per segment with correction=exp and no ref_dt");
  const int n = opt.n;
  std::vector<Step> steps;
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(seg.length > 0.0)) continue;
    const double ds = seg.scalar_exit - seg.scalar_far;
    for (int k = 0; k < n; ++k) {  // far -> near, riemann.cpp's sample positions bit for bit
      Step st;
      st.segment = j;
      st.h = seg.length / n;
      st.dh_dlength = 1.0 / n;
      const double w = (k + 0.5) / n;
      st.p[0] = {seg.scalar_far + w * ds, 1.0 - w, w, 1.0, 1.0, ds};
      steps.push_back(st);
    }
  }
  return march_gradient(tf, ray, steps);
}

RayGradient nerf_ray_gradient(const TransferFunctions& tf, const Ray& ray, const NerfOptions& opt,
                              bool piecewise_linear) {
  const int n = opt.n;
  std::vector<Step> steps;
  // NeRF 2020's extra far sample (far -> near: it comes first).
  bool any_length = false;
  for (const Segment& seg : ray.segments) any_length = any_length || seg.length > 0.0;
  if (!piecewise_linear && opt.last_inf && any_length) {
    Step st;
    st.segment = 0;
    st.h = kNerfLastDelta;
    st.p[0] = {ray.segments.front().scalar_far, 1.0, 0.0, 1.0, 1.0,
               ray.segments.front().scalar_exit - ray.segments.front().scalar_far};
    steps.push_back(st);
  }
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(seg.length > 0.0)) continue;
    const double ds = seg.scalar_far - seg.scalar_exit;
    // nerf.cpp's scalar k intervals from the exit end (k = n is the far end exactly).
    const auto at = [&](double k) -> SamplePoint {
      if (k == n) return {seg.scalar_far, 1.0, 0.0, 0.0, 0.0, -ds};  // interior toward the exit
      const double w = k / n;
      return {seg.scalar_exit + w * ds, w, 1.0 - w, 0.0, 0.0, k == 0 ? ds : -ds};
    };
    for (int k = n - 1; k >= 0; --k) {  // far -> near
      Step st;
      st.segment = j;
      st.h = seg.length / n;
      st.dh_dlength = 1.0 / n;
      if (!piecewise_linear) {
        st.p[0] = at(k + (opt.at == NerfSampleAt::mid ? 0.5 : 0.0));
        st.p[0].w_rho = st.p[0].w_kappa = 1.0;
      } else {
        // Interval k+1 of nerf.cpp: between samples k (eye side) and k + 1.
        st.count = 2;
        st.p[0] = at(k);
        st.p[1] = at(k + 1);
        st.p[0].w_rho = st.p[1].w_rho = 0.5;
        st.p[0].w_kappa = opt.mid_colour ? 0.5 : 1.0;
        st.p[1].w_kappa = opt.mid_colour ? 0.5 : 0.0;
      }
      steps.push_back(st);
    }
  }
  return march_gradient(tf, ray, steps);
}

}  // namespace rayint
