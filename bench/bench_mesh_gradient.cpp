// Cost of the mesh gradient (render/mesh_gradient.hpp, issue 28) against the forward render it
// differentiates, per pixel ray, single-threaded, on cases/mesh-ball-radial.json over the rays of
// every 8th pixel of its camera:
//   BM_mesh_render_ray        the forward pixel: traversal (mesh_ray) + exact on its segments;
//   BM_mesh_gradient_ray      pixel_jacobian: traversal + exact gradient + the chain to the
//                             vertex scalars and positions;
// and per image (the camera shrunk to 96 x 96, one thread), what `rayint render` and
// `rayint render --loss-target T --grad-out G [--grad-positions-out P]` compute:
//   BM_mesh_render_image           render_mesh with exact;
//   BM_mesh_loss_gradient_image/0  image_loss_gradient, vertex scalars only (--grad-out);
//   BM_mesh_loss_gradient_image/1  ... and vertex positions (--grad-positions-out).
// The ratios gradient / render are the figures quoted in reports/gradients/README.md.
// Run: build/bench/rayint_bench --benchmark_filter='BM_mesh_(render|gradient)' --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median)
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <vector>

#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/render/mesh_gradient.hpp"
#include "rayint/render/mesh_render.hpp"

namespace {

using namespace rayint;

struct MeshGradientBench {
  MeshCase mc;
  std::unique_ptr<TetTraversal> mesh;
  std::vector<ViewRay> rays;
  std::unique_ptr<RayIntegrator> exact;
  MeshCase small;  // the case with a 96 x 96 camera
  Image target;

  MeshGradientBench() {
    const char* dir = std::getenv("RAYINT_CASES_DIR");
    const std::filesystem::path base =
        dir ? std::filesystem::path(dir) : std::filesystem::path(__FILE__).parent_path().parent_path() / "cases";
    mc = read_mesh_case_file((base / "mesh-ball-radial.json").string());
    mesh = std::make_unique<TetTraversal>(mc.mesh, mc.mesh_source);
    for (int y = 0; y < mc.camera->height; y += 8)
      for (int x = 0; x < mc.camera->width; x += 8) rays.push_back(mc.camera->ray_for_pixel(x, y));
    exact = make_integrator(parse_method_spec("exact"), mc.transfer);
    small = mc;
    small.camera->width = small.camera->height = 96;
    target = Image(96, 96);  // black: the loss is the image's own sum of squares
  }
  static MeshGradientBench& get() {
    static MeshGradientBench b;
    return b;
  }
};

void BM_mesh_render_ray(benchmark::State& state) {
  MeshGradientBench& b = MeshGradientBench::get();
  std::size_t i = 0;
  for (auto _ : state) {
    const Ray ray = mesh_ray(*b.mesh, b.rays[i++ % b.rays.size()], b.mc.background);
    benchmark::DoNotOptimize(b.exact->integrate(ray, nullptr));
  }
}
BENCHMARK(BM_mesh_render_ray);

void BM_mesh_gradient_ray(benchmark::State& state) {
  MeshGradientBench& b = MeshGradientBench::get();
  std::size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(pixel_jacobian(*b.mesh, b.mc.transfer, b.rays[i++ % b.rays.size()], b.mc.background));
}
BENCHMARK(BM_mesh_gradient_ray);

void BM_mesh_render_image(benchmark::State& state) {
  MeshGradientBench& b = MeshGradientBench::get();
  MeshRenderSettings settings;
  settings.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(render_mesh(b.small, *b.mesh, *b.exact, nullptr, settings));
}
// Process CPU time: render_mesh runs its rows on a worker thread even with threads = 1, so the
// main thread's CPU time is not the work; on the shared machine wall time is not either.
BENCHMARK(BM_mesh_render_image)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

void BM_mesh_loss_gradient_image(benchmark::State& state) {
  MeshGradientBench& b = MeshGradientBench::get();
  const bool positions = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(image_loss_gradient(b.small, *b.mesh, b.target, 1, positions));
}
BENCHMARK(BM_mesh_loss_gradient_image)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace
