// Cost of the exact trilinear image (grid/trilinear_integral.hpp): a 512 x 512 orthographic
// image of a smooth 256^3 volume (0.5 + 0.4 sin(x/9) cos(y/13) sin(z/7 + 0.3) on unit spacing),
// viewed along (0.3, 0.2, 1) so every ray crosses cubes of all three axes, with a grey transfer
// function of 4 density breakpoints and a 4-point colour ramp (most cubes are one piece; those
// the scalar crosses a breakpoint in are cut).
//   BM_trilinear_image_2threads  the whole image on 2 threads (parallel_for over rows), seconds;
//   BM_trilinear_ray             one ray of that image through the middle, per ray.
// Run: build/bench/rayint_bench --benchmark_filter=BM_trilinear
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "rayint/core/parallel.hpp"
#include "rayint/grid/trilinear_integral.hpp"

namespace {

using namespace rayint;

constexpr int kN = 256;
constexpr int kPixels = 512;

const VoxelGrid& volume() {
  static const VoxelGrid g = [] {
    std::vector<double> v(static_cast<std::size_t>(kN) * kN * kN);
    std::size_t n = 0;
    for (int k = 0; k < kN; ++k)
      for (int j = 0; j < kN; ++j)
        for (int i = 0; i < kN; ++i)
          v[n++] = 0.5 + 0.4 * std::sin(i / 9.0) * std::cos(j / 13.0) * std::sin(k / 7.0 + 0.3);
    return VoxelGrid({kN, kN, kN}, Vec3::Zero(), Vec3::Ones(), std::move(v));
  }();
  return g;
}

TransferFunctions transfer() {
  TransferFunctions tf;
  const PiecewiseLinear rho{{0.3, 0.5, 0.7, 0.85}, {0.0, 0.02, 0.005, 0.05}};
  for (int c = 0; c < kChannels; ++c) tf.density[static_cast<std::size_t>(c)] = rho;
  tf.color[0] = {{0.2, 0.5, 0.9}, {0.1, 0.9, 1.0}};
  tf.color[1] = {{0.2, 0.6, 0.9}, {0.3, 0.5, 0.2}};
  tf.color[2] = {{0.2, 0.4, 0.9}, {1.0, 0.4, 0.1}};
  return tf;
}

ViewRay pixel_ray(int px, int py) {
  const Vec3 dir = Vec3(0.3, 0.2, 1.0).normalized();
  const Vec3 e1 = dir.cross(Vec3::UnitY()).normalized(), e2 = dir.cross(e1);
  const Vec3 centre = Vec3::Constant(0.5 * (kN - 1));
  const double pitch = 450.0 / kPixels;
  const Vec3 p = centre + ((px + 0.5) - 0.5 * kPixels) * pitch * e1 + ((py + 0.5) - 0.5 * kPixels) * pitch * e2;
  return {p - 400.0 * dir, dir};
}

void BM_trilinear_image_2threads(benchmark::State& state) {
  const VoxelGrid& g = volume();
  const TransferFunctions tf = transfer();
  const TrilinearIntegrator integrator(tf);
  std::vector<double> image(static_cast<std::size_t>(kPixels) * kPixels * 3);
  long long cubes = 0;
  for (auto _ : state) {
    std::vector<long long> worker_cubes(2, 0);
    parallel_for(kPixels, 2, [&](long long row, unsigned worker) {
      for (int px = 0; px < kPixels; ++px) {
        const TrilinearRayResult r = integrator.integrate(g, pixel_ray(px, static_cast<int>(row)), Rgb{});
        for (int c = 0; c < 3; ++c)
          image[3 * (static_cast<std::size_t>(row) * kPixels + static_cast<std::size_t>(px)) + static_cast<std::size_t>(c)] =
              r.intensity[static_cast<std::size_t>(c)];
        worker_cubes[worker] += r.cubes;
      }
    });
    cubes = worker_cubes[0] + worker_cubes[1];
    benchmark::DoNotOptimize(image.data());
  }
  state.counters["cubes"] = static_cast<double>(cubes);
  state.counters["cubes/s"] = benchmark::Counter(static_cast<double>(cubes) * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_trilinear_image_2threads)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_trilinear_ray(benchmark::State& state) {
  const VoxelGrid& g = volume();
  const TransferFunctions tf = transfer();
  const TrilinearIntegrator integrator(tf);
  const ViewRay ray = pixel_ray(kPixels / 2, kPixels / 2);
  for (auto _ : state) benchmark::DoNotOptimize(integrator.integrate(g, ray, Rgb{}));
}
BENCHMARK(BM_trilinear_ray)->Unit(benchmark::kMicrosecond);

}  // namespace
