// The references of the scene terms; see term_references.hpp.
#include "rayint/scene/term_references.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <queue>
#include <vector>

#include "rayint/scene/shadowing.hpp"

namespace rayint {
namespace {

struct Panel {
  double a = 0.0, b = 0.0;
  Rgb value{}, error{};
  double worst = 0.0;  // max channel error, for the priority queue
  bool operator<(const Panel& o) const { return worst < o.worst; }
};

Panel gk15(const std::function<Rgb(double)>& f, double a, double b, long long& evals) {
  using GK = boost::math::quadrature::gauss_kronrod<double, 15>;
  using G = boost::math::quadrature::gauss<double, 7>;
  const auto& x = GK::abscissa();
  const auto& wk = GK::weights();
  const auto& wg = G::weights();
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  Rgb k{}, g{};
  const Rgb f0 = f(mid);
  for (int c = 0; c < kChannels; ++c) {
    k[c] = f0[c] * wk[0];
    g[c] = f0[c] * wg[0];
  }
  for (std::size_t i = 1; i < x.size(); ++i) {
    const Rgb fp = f(mid + half * x[i]);
    const Rgb fm = f(mid - half * x[i]);
    for (int c = 0; c < kChannels; ++c) {
      k[c] += (fp[c] + fm[c]) * wk[i];
      if (i % 2 == 0) g[c] += (fp[c] + fm[c]) * wg[i / 2];
    }
  }
  evals += 15;
  Panel p{a, b, {}, {}, 0.0};
  for (int c = 0; c < kChannels; ++c) {
    p.value[c] = k[c] * half;
    p.error[c] = std::abs((k[c] - g[c]) * half);
    p.worst = std::max(p.worst, p.error[c]);
  }
  return p;
}

Rgb exp_neg(const Rgb& tau) { return {std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])}; }

// tau(t) from t_enter along a ray, from cached knots.
class ViewDepth {
 public:
  ViewDepth(const Medium& m, const ViewRay& ray, double t0, double t1, const QuadratureOptions& opt,
            long long& evals, bool& converged)
      : m_(m), ray_(ray), t0_(t0), opt_(opt), evals_(evals), converged_(converged) {
    opt_.rtol = opt.rtol * 0.1;
    opt_.atol = opt.atol * 0.1;
    h_ = (t1 - t0) / kKnots;
    knots_.assign(kKnots + 1, Rgb{});
    for (int i = 0; i < kKnots; ++i) {
      const QuadratureResult r = integrate_adaptive(sigma(), t0 + i * h_, t0 + (i + 1) * h_, opt_);
      evals_ += r.evaluations;
      converged_ = converged_ && r.converged;
      for (int c = 0; c < kChannels; ++c) knots_[i + 1][c] = knots_[i][c] + r.value[c];
    }
  }
  Rgb operator()(double t) const {
    const int i = std::clamp(static_cast<int>(std::floor((t - t0_) / h_ + 0.5)), 0, kKnots);
    const double tk = t0_ + i * h_;
    if (t == tk) return knots_[i];
    const QuadratureResult r = integrate_adaptive(sigma(), tk, t, opt_);
    evals_ += r.evaluations;
    converged_ = converged_ && r.converged;
    Rgb out = knots_[i];
    for (int c = 0; c < kChannels; ++c) out[c] += r.value[c];  // r is signed for t < tk
    return out;
  }
  const Rgb& total() const { return knots_.back(); }

 private:
  std::function<Rgb(double)> sigma() const {
    return [this](double t) { return m_.extinction(ray_.origin + ray_.direction * t); };
  }
  static constexpr int kKnots = 64;
  const Medium& m_;
  ViewRay ray_;
  double t0_, h_ = 0.0;
  QuadratureOptions opt_;
  long long& evals_;
  bool& converged_;
  std::vector<Rgb> knots_;
};

}  // namespace

QuadratureResult integrate_adaptive(const std::function<Rgb(double)>& f, double a, double b,
                                    const QuadratureOptions& options) {
  QuadratureResult out;
  if (!(b != a)) return out;
  const double sign = b > a ? 1.0 : -1.0;
  if (b < a) std::swap(a, b);
  std::priority_queue<Panel> heap;
  // Starting panels of at most options.panel_length, so that no feature hides between nodes.
  const double panels_wanted = std::ceil((b - a) / options.panel_length);
  const int panels = std::isfinite(panels_wanted)
                         ? static_cast<int>(std::clamp(panels_wanted, 1.0, std::max(1.0, 0.5 * options.max_intervals)))
                         : 1;
  Rgb total{}, err{};
  for (int i = 0; i < panels; ++i) {
    const double pa = i == 0 ? a : a + (b - a) * i / panels;
    const double pb = i + 1 == panels ? b : a + (b - a) * (i + 1) / panels;
    const Panel p = gk15(f, pa, pb, out.evaluations);
    for (int c = 0; c < kChannels; ++c) {
      total[c] += p.value[c];
      err[c] += p.error[c];
    }
    heap.push(p);
  }
  int intervals = panels;
  auto done = [&] {
    for (int c = 0; c < kChannels; ++c)
      if (err[c] > std::max(options.atol, options.rtol * std::abs(total[c]))) return false;
    return true;
  };
  while (!done()) {
    if (intervals >= options.max_intervals) {
      out.converged = false;
      break;
    }
    const Panel p = heap.top();
    heap.pop();
    const double m = 0.5 * (p.a + p.b);
    if (!(m > p.a && m < p.b)) {  // cannot split further in double
      out.converged = false;
      heap.push(p);
      break;
    }
    const Panel l = gk15(f, p.a, m, out.evaluations);
    const Panel r = gk15(f, m, p.b, out.evaluations);
    for (int c = 0; c < kChannels; ++c) {
      total[c] += l.value[c] + r.value[c] - p.value[c];
      err[c] += l.error[c] + r.error[c] - p.error[c];
    }
    heap.push(l);
    heap.push(r);
    ++intervals;
  }
  // Re-sum from the panels (the running update accumulates rounding).
  Rgb sum{}, esum{};
  while (!heap.empty()) {
    for (int c = 0; c < kChannels; ++c) {
      sum[c] += heap.top().value[c];
      esum[c] += heap.top().error[c];
    }
    heap.pop();
  }
  for (int c = 0; c < kChannels; ++c) {
    out.value[c] = sign * sum[c];
    out.error[c] = esum[c];
  }
  return out;
}

Rgb reference_light_transmittance(const Scene& scene, std::size_t light, const Vec3& p,
                                  const QuadratureOptions& options, long long& evaluations,
                                  bool& converged) {
  const LightArrival arrival = scene.lights[light].at(p);
  const Vec3 u = -arrival.propagation;
  const RaySpan span = scene.medium.bounds().clip({p, u});
  if (!span.hit) return {1.0, 1.0, 1.0};
  const double t_end = std::min(span.t_exit, arrival.distance);
  if (!(t_end > span.t_enter)) return {1.0, 1.0, 1.0};
  QuadratureOptions opt = options;
  opt.rtol *= 0.1;
  opt.atol *= 0.1;
  opt.panel_length = scene.medium.field().feature_length();
  const QuadratureResult r = integrate_adaptive(
      [&](double t) { return scene.medium.extinction(p + u * t); }, span.t_enter, t_end, opt);
  evaluations += r.evaluations;
  converged = converged && r.converged;
  return exp_neg(r.value);
}

ReferenceValue reference_source_term(const Scene& scene, const ViewRay& ray, const SourceFn& source,
                                     bool absorption, bool shadows) {
  ReferenceValue out;
  const RaySpan span = scene.medium.bounds().clip(ray);
  if (!span.hit) return out;
  QuadratureOptions opt = scene.reference;
  opt.panel_length = scene.medium.field().feature_length();
  long long evals = 0;
  bool converged = true;
  std::unique_ptr<ViewDepth> depth;
  if (absorption) depth = std::make_unique<ViewDepth>(scene.medium, ray, span.t_enter, span.t_exit, opt, evals, converged);
  const LightTransmittanceFn light_fn = [&](std::size_t l, const Vec3& p) -> Rgb {
    if (!shadows) return {1.0, 1.0, 1.0};
    return reference_light_transmittance(scene, l, p, opt, evals, converged);
  };
  const QuadratureResult r = integrate_adaptive(
      [&](double t) -> Rgb {
        const Vec3 p = ray.origin + ray.direction * t;
        const Optics o = scene.medium.optics_at_density(scene.medium.density(p));
        Rgb s = source(p, o, light_fn);
        if (depth) {
          const Rgb T = exp_neg((*depth)(t));
          for (int c = 0; c < kChannels; ++c) s[c] *= T[c];
        }
        return s;
      },
      span.t_enter, span.t_exit, opt);
  out.value = r.value;
  out.error_estimate = r.error;
  out.evaluations = evals + r.evaluations;
  out.converged = converged && r.converged;
  return out;
}

ReferenceValue reference_transmittance(const Scene& scene, const ViewRay& ray) {
  ReferenceValue out;
  out.value = {1.0, 1.0, 1.0};
  const RaySpan span = scene.medium.bounds().clip(ray);
  if (!span.hit) return out;
  QuadratureOptions opt = scene.reference;
  opt.panel_length = scene.medium.field().feature_length();
  const QuadratureResult r = integrate_adaptive(
      [&](double t) { return scene.medium.extinction(ray.origin + ray.direction * t); },
      span.t_enter, span.t_exit, opt);
  out.value = exp_neg(r.value);
  for (int c = 0; c < kChannels; ++c) out.error_estimate[c] = out.value[c] * r.error[c];
  out.evaluations = r.evaluations;
  out.converged = r.converged;
  return out;
}

}  // namespace rayint
