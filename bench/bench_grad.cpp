// The cost of the exact gradient of a ray against its forward exact integral (issue 28's
// "full gradient at most ~3x the forward exact"), on the same rays:
// Like for like, the transfer functions prepared outside the loop (each ray has its own):
//   BM_exact_ray/SET          ExactIntegrator (the default batch path) on every ray of SET;
//   BM_exact_ray_scalar/SET   exact:path=scalar on the same rays;
//   BM_exact_grad_prepared/SET  ExactRayGradient (forward + every derivative) on the same rays,
//                             one RayGradient's storage reused.
// Preparation included, per ray:
//   BM_exact_ray_unprepared/SET  an ExactIntegrator built for the ray's functions, then integrate;
//   BM_exact_grad/SET         the free exact_ray_gradient(tf, ray), a new RayGradient per ray (its
//                             per-thread preparation is rebuilt for every ray: each has its own
//                             functions);
//   BM_exact_grad_segments/SET  the free function with GradientBlocks::segments (no node blocks:
//                             what the mesh and grid image losses compute), storage reused.
// SET 0: 20 rays of every stress regime (generators/regimes.hpp, seed 28; long_ray cut to 200
// segments); SET 1: 4 long_ray rays of 10^4 segments.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_grad.hpp"

namespace {

struct RaySet {
  std::vector<rayint::RaySample> rays;
  std::vector<std::unique_ptr<rayint::ExactIntegrator>> batch, scalar;
  std::vector<rayint::ExactRayGradient> grad;
};

const RaySet& ray_set(int which) {
  static RaySet sets[2];
  RaySet& s = sets[which];
  if (s.rays.empty()) {
    std::mt19937_64 rng(28);
    if (which == 0) {
      for (const rayint::Regime r : rayint::stress_regimes())
        for (int i = 0; i < 20; ++i) {
          rayint::RaySample rs = rayint::sample_ray(r, rng);
          if (rs.ray.segments.size() > 200) rs.ray.segments.resize(200);
          s.rays.push_back(std::move(rs));
        }
    } else {
      for (int i = 0; i < 4; ++i) s.rays.push_back(rayint::sample_ray(rayint::Regime::long_ray, rng));
    }
    for (const rayint::RaySample& rs : s.rays) {
      s.batch.push_back(std::make_unique<rayint::ExactIntegrator>(rs.transfer));
      s.scalar.push_back(std::make_unique<rayint::ExactIntegrator>(rs.transfer, rayint::ExactIntegrator::Path::scalar));
      s.grad.emplace_back(rs.transfer);
    }
  }
  return s;
}

void BM_exact_ray(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  for (auto _ : state)
    for (std::size_t i = 0; i < s.rays.size(); ++i)
      benchmark::DoNotOptimize(s.batch[i]->integrate(s.rays[i].ray, nullptr));
}

void BM_exact_ray_scalar(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  for (auto _ : state)
    for (std::size_t i = 0; i < s.rays.size(); ++i)
      benchmark::DoNotOptimize(s.scalar[i]->integrate(s.rays[i].ray, nullptr));
}

void BM_exact_ray_unprepared(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  for (auto _ : state)
    for (const rayint::RaySample& rs : s.rays)
      benchmark::DoNotOptimize(rayint::ExactIntegrator(rs.transfer).integrate(rs.ray, nullptr));
}

void BM_exact_grad_prepared(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  rayint::RayGradient g;
  for (auto _ : state)
    for (std::size_t i = 0; i < s.rays.size(); ++i) {
      s.grad[i](s.rays[i].ray, g);
      benchmark::DoNotOptimize(g.intensity);
    }
}

void BM_exact_grad(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  for (auto _ : state)
    for (const rayint::RaySample& rs : s.rays)
      benchmark::DoNotOptimize(rayint::exact_ray_gradient(rs.transfer, rs.ray));
}

void BM_exact_grad_segments(benchmark::State& state) {
  const RaySet& s = ray_set(static_cast<int>(state.range(0)));
  rayint::RayGradient g;
  for (auto _ : state)
    for (const rayint::RaySample& rs : s.rays) {
      rayint::exact_ray_gradient(rs.transfer, rs.ray, g, rayint::GradientBlocks::segments);
      benchmark::DoNotOptimize(g.intensity);
    }
}

}  // namespace

BENCHMARK(BM_exact_ray)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_exact_ray_scalar)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_exact_grad_prepared)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_exact_ray_unprepared)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_exact_grad)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_exact_grad_segments)->DenseRange(0, 1)->Unit(benchmark::kMicrosecond);
