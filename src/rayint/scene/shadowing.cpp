#include "rayint/scene/shadowing.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rayint/core/cpu_clock.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/media/riemann_march.hpp"

namespace rayint {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Rgb exp_neg(const Rgb& tau) { return {std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])}; }

}  // namespace

double light_path_length(const Scene& scene, const Vec3& p, const LightArrival& arrival) {
  const ViewRay toward{p, -arrival.propagation};
  const RaySpan span = scene.medium.bounds().clip(toward);
  if (!span.hit) return 0.0;
  return std::max(0.0, std::min(span.t_exit, arrival.distance) - span.t_enter);
}

ShadowRays::ShadowRays(const Scene& scene, int n) : scene_(scene), n_(n) {
  if (n < 1) throw std::invalid_argument("shadow_rays: n must be >= 1");
}

Rgb ShadowRays::transmittance(std::size_t light, const Vec3& p, EffectWork& work) const {
  const Clock::time_point t0 = Clock::now();
  const double c0 = thread_cpu_seconds();
  const LightArrival arrival = scene_.lights[light].at(p);
  const Vec3 u = -arrival.propagation;
  const ViewRay toward{p, u};
  const RaySpan span = scene_.medium.bounds().clip(toward);
  Rgb tau{};
  if (span.hit) {
    const double t_end = std::min(span.t_exit, arrival.distance);
    if (t_end - span.t_enter > 0.0) {
      tau = riemann_optical_depth(scene_.medium, toward, span.t_enter, t_end, n_);
      work.shadow_samples += n_;
    }
  }
  ++work.shadow_rays;
  work.cpu_seconds += thread_cpu_seconds() - c0;
  work.seconds += seconds_since(t0);
  return exp_neg(tau);
}

LightGrid::LightGrid(const Scene& scene, int resolution, unsigned threads)
    : scene_(scene), res_(resolution) {
  if (resolution < 2) throw std::invalid_argument("two_pass: grid must be >= 2");
  const Bounds b = scene.medium.bounds();
  if (!b.finite()) throw std::invalid_argument("two_pass needs a bounded medium (not a slab)");
  lower_ = b.lower;
  spacing_ = (b.upper - b.lower) / (res_ - 1);
  const Clock::time_point t0 = Clock::now();
  const double c0 = process_cpu_seconds();
  grids_.resize(scene.lights.size());
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    grids_[l].assign(static_cast<std::size_t>(res_) * res_ * res_, Rgb{1.0, 1.0, 1.0});
    if (scene.lights[l].kind == Light::Kind::directional)
      propagate_directional(l);
    else
      march_point(l, threads);
  }
  setup_seconds_ = seconds_since(t0);
  setup_cpu_seconds_ = process_cpu_seconds() - c0;
}

Vec3 LightGrid::vertex(int i, int j, int k) const {
  return lower_ + Vec3(i * spacing_.x(), j * spacing_.y(), k * spacing_.z());
}

void LightGrid::propagate_directional(std::size_t l) {
  const Vec3 w = scene_.lights[l].direction;
  int a = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(w[d]) > std::abs(w[a])) a = d;
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const int step = w[a] > 0.0 ? 1 : -1;
  const int first = step > 0 ? 0 : res_ - 1;
  const double h = spacing_[a] / std::abs(w[a]);  // path length between two layers
  const Vec3 back = -w * h;                         // from a vertex to the previous layer
  std::vector<Rgb>& T = grids_[l];
  auto at = [&](int ia, int ib, int ic) -> Rgb& {
    int idx[3];
    idx[a] = ia;
    idx[b] = ib;
    idx[c] = ic;
    return T[index(idx[0], idx[1], idx[2])];
  };
  const Medium& m = scene_.medium;
  // Layer `first` is where the light enters the bounds: T = 1 there (vacuum outside).
  for (int ia = first + step; ia >= 0 && ia < res_; ia += step) {
    for (int ib = 0; ib < res_; ++ib) {
      for (int ic = 0; ic < res_; ++ic) {
        int idx[3];
        idx[a] = ia;
        idx[b] = ib;
        idx[c] = ic;
        const Vec3 v = vertex(idx[0], idx[1], idx[2]);
        const Vec3 q = v + back;
        const double fb = (q[b] - lower_[b]) / spacing_[b];
        const double fc = (q[c] - lower_[c]) / spacing_[c];
        const Rgb sv = m.extinction(v);
        setup_samples_ += 1;
        Rgb result{};
        if (fb < 0.0 || fc < 0.0 || fb > res_ - 1 || fc > res_ - 1) {
          // The light path leaves the bounds sideways before reaching the previous layer:
          // integrate the part inside with the trapezoid rule to the exit point.
          const double len = light_path_length(scene_, v, scene_.lights[l].at(v));
          const Rgb se = m.extinction(v - w * len);
          setup_samples_ += 1;
          for (int ch = 0; ch < kChannels; ++ch) result[ch] = std::exp(-0.5 * len * (sv[ch] + se[ch]));
        } else {
          const int jb = std::min(res_ - 2, static_cast<int>(fb));
          const int jc = std::min(res_ - 2, static_cast<int>(fc));
          const double ub = fb - jb, uc = fc - jc;
          const int prev = ia - step;
          const Rgb& t00 = at(prev, jb, jc);
          const Rgb& t10 = at(prev, jb + 1, jc);
          const Rgb& t01 = at(prev, jb, jc + 1);
          const Rgb& t11 = at(prev, jb + 1, jc + 1);
          const Rgb sq = m.extinction(q);
          setup_samples_ += 1;
          for (int ch = 0; ch < kChannels; ++ch) {
            const double tq = (1 - ub) * (1 - uc) * t00[ch] + ub * (1 - uc) * t10[ch] +
                              (1 - ub) * uc * t01[ch] + ub * uc * t11[ch];
            result[ch] = tq * std::exp(-0.5 * h * (sq[ch] + sv[ch]));
          }
        }
        at(ia, ib, ic) = result;
      }
    }
  }
}

void LightGrid::march_point(std::size_t l, unsigned threads) {
  const double hmin = spacing_.minCoeff();
  std::vector<long long> samples(resolve_threads(threads), 0);
  parallel_for(res_, threads, [&](long long k, unsigned worker) {
    for (int j = 0; j < res_; ++j)
      for (int i = 0; i < res_; ++i) {
        const Vec3 v = vertex(i, j, static_cast<int>(k));
        const LightArrival arrival = scene_.lights[l].at(v);
        const double len = light_path_length(scene_, v, arrival);
        const int n = std::max(1, static_cast<int>(std::ceil(len / hmin)));
        const Rgb tau = riemann_optical_depth(scene_.medium, {v, -arrival.propagation}, 0.0, len, n);
        samples[worker] += n;
        grids_[l][index(i, j, static_cast<int>(k))] = exp_neg(tau);
      }
  });
  for (long long s : samples) setup_samples_ += s;
}

Rgb LightGrid::transmittance(std::size_t light, const Vec3& p, EffectWork& work) const {
  ++work.lookups;
  const Vec3 f = (p - lower_).cwiseQuotient(spacing_);
  int i0[3];
  double u[3];
  for (int a = 0; a < 3; ++a) {
    const double x = std::min(std::max(f[a], 0.0), static_cast<double>(res_ - 1));
    i0[a] = std::min(res_ - 2, static_cast<int>(x));
    u[a] = x - i0[a];
  }
  const std::vector<Rgb>& T = grids_[light];
  Rgb out{};
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const double wgt = (dx ? u[0] : 1 - u[0]) * (dy ? u[1] : 1 - u[1]) * (dz ? u[2] : 1 - u[2]);
        const Rgb& t = T[index(i0[0] + dx, i0[1] + dy, i0[2] + dz)];
        for (int c = 0; c < kChannels; ++c) out[c] += wgt * t[c];
      }
  return out;
}

std::unique_ptr<Shadowing> make_shadowing(const Scene& scene, unsigned threads) {
  if (!scene.has("shadows")) return std::make_unique<NoShadows>();
  const auto it = scene.methods.find("shadows");
  MethodSpec spec;
  if (it != scene.methods.end()) {
    spec = it->second;
  } else {
    spec.name = "shadow_rays";
  }
  if (spec.name == "two_pass")
    return std::make_unique<LightGrid>(scene, static_cast<int>(spec.number("grid", 64)), threads);
  if (spec.name == "shadow_rays") {
    double fallback = 128;
    const auto ss = scene.methods.find("single_scattering");
    if (ss != scene.methods.end()) fallback = ss->second.number("n", 128);
    return std::make_unique<ShadowRays>(scene, static_cast<int>(spec.number("n", fallback)));
  }
  throw std::invalid_argument("shadows: unknown method " + spec.name +
                              " (expected shadow_rays or two_pass)");
}

}  // namespace rayint
