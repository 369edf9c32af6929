// Reverse-mode derivative of the Riemann sum of riemann.cpp (n midpoint samples per segment,
// exact opacity): per sample, scalar s = s_far + ((k + 1/2)/n)(s_exit - s_far), h = L/n,
// x = rho(s) h, transparency e^{-x}, colour kappa(s) (1 - e^{-x}); back to front
// I <- colour + e^{-x} I from the background. The adjoint of I after a sample is the product of
// the transparencies nearer the eye; each sample passes it on to x, kappa, h and s, and from
// there to the length, the end scalars and the transfer-function nodes.
#include "rayint/integrators/riemann_grad.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace rayint {

RayGradient riemann_ray_gradient(const TransferFunctions& tf, const Ray& ray, const RiemannOptions& opt) {
  if (opt.dt > 0.0 || opt.opacity != OpacityRule::exact)
    throw std::invalid_argument(
        "riemann gradient: only n samples per segment with correction=exp and no ref_dt");
  const int n = opt.n;
  RayGradient g = RayGradient::zeros(tf, ray);
  struct Sample {
    std::size_t segment;
    double w;  // (k + 1/2)/n
    double s, h;
    double incoming[kChannels];  // I before the sample
    double transparency[kChannels], alpha[kChannels], rho[kChannels], kappa[kChannels];
  };
  std::vector<Sample> samples;
  Rgb I = ray.background;
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(seg.length > 0.0)) continue;
    const double h = seg.length / n;
    const double ds = seg.scalar_exit - seg.scalar_far;
    for (int k = 0; k < n; ++k) {
      Sample sm{};
      sm.segment = j;
      sm.w = (k + 0.5) / n;
      sm.s = seg.scalar_far + sm.w * ds;  // riemann.cpp's sample position, bit for bit
      sm.h = h;
      for (int c = 0; c < kChannels; ++c) {
        sm.rho[c] = tf.density[c](sm.s);
        sm.kappa[c] = tf.color[c](sm.s);
        const StepOpacity o = step_opacity(sm.rho[c] * h);
        sm.alpha[c] = o.alpha;
        sm.transparency[c] = o.transparency;
        sm.incoming[c] = I[c];
        I[c] = sm.kappa[c] * o.alpha + o.transparency * I[c];
      }
      samples.push_back(sm);
    }
  }
  g.intensity = I;
  Rgb adjoint{1.0, 1.0, 1.0};
  for (std::size_t q = samples.size(); q-- > 0;) {
    const Sample& sm = samples[q];
    for (int c = 0; c < kChannels; ++c) {
      const double colour_bar = adjoint[c];
      // I = kappa (1 - tr) + tr I_in: d/d tr = I_in - kappa; d tr/dx = -tr.
      const double x_bar = -adjoint[c] * (sm.incoming[c] - sm.kappa[c]) * sm.transparency[c];
      const double kappa_bar = colour_bar * sm.alpha[c];
      const double rho_bar = x_bar * sm.h;
      const double h_bar = x_bar * sm.rho[c];
      g.length[sm.segment][c] += h_bar / n;
      const NodeWeights nr = node_weights(tf.density[c], sm.s, sm.s);
      const NodeWeights nk = node_weights(tf.color[c], sm.s, sm.s);
      for (int i = 0; i < nr.count; ++i) {
        g.density[c][nr.node[i]].value += rho_bar * nr.w[i];
        g.density[c][nr.node[i]].position += rho_bar * nr.dp[i];
      }
      for (int i = 0; i < nk.count; ++i) {
        g.color[c][nk.node[i]].value += kappa_bar * nk.w[i];
        g.color[c][nk.node[i]].position += kappa_bar * nk.dp[i];
      }
      const double s_bar = rho_bar * nr.slope + kappa_bar * nk.slope;
      g.scalar_far[sm.segment][c] += s_bar * (1.0 - sm.w);
      g.scalar_exit[sm.segment][c] += s_bar * sm.w;
      adjoint[c] *= sm.transparency[c];
    }
  }
  g.background = adjoint;
  return g;
}

}  // namespace rayint
