// Mesh-level cost of the own interpolation against VTK's split (issue 29: a hexahedral mesh at
// <= 3x the time of the same mesh split into tetrahedra). One mesh: a structured 12 x 12 x 12
// grid of hexahedra on [0, 1]^3, each k-layer turned about the z axis by 3 degrees more than the
// one below (every hexahedron twisted, faces bilinear patches, not planes), the field of the
// reader fixtures s = 0.5 + 0.3 sin(2x) cos(y) + 0.25 z + 0.2 xyz, the transfer functions of
// bench_cells.cpp (tests/cell_samples.hpp breakpoint_tf). 256 rays (16 x 16 parallel rays across
// the box, tilted), single-threaded:
//   BM_mesh/own    CellTraversal: trace + LinearCellIntegrator on every chord, composited
//   BM_mesh/own_trace_only  the traversal alone (its share of BM_mesh/own)
//   BM_mesh/split  the same CellMesh through split_cells (VTK's structured 5-tet rule), then
//                  TetTraversal + the `exact` method: what `--cells split` pays
//   BM_mesh/own_box, BM_mesh/own_box_trace_only, BM_mesh/split_box   the same on the untwisted
//                  grid (axis-aligned cubes: affine cells, the own path's polynomial branch)
// Time per iteration = 256 rays; the ratio own / split is the figure.
// Run: build/bench/rayint_bench --benchmark_filter=BM_mesh/ --benchmark_repetitions=3
//      --benchmark_report_aggregates_only=true      (quote the medians)
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "cell_samples.hpp"  // test::breakpoint_tf

namespace {

using namespace rayint;

// twist: degrees per k-layer (0: axis-aligned cubes).
CellMesh twisted_grid(int n, double twist = 3.0) {
  CellMesh m;
  const int np = n + 1;
  for (int k = 0; k < np; ++k) {
    const double z = static_cast<double>(k) / n, a = twist * k * M_PI / 180.0;
    for (int j = 0; j < np; ++j)
      for (int i = 0; i < np; ++i) {
        const double x = static_cast<double>(i) / n - 0.5, y = static_cast<double>(j) / n - 0.5;
        m.points.emplace_back(0.5 + std::cos(a) * x - std::sin(a) * y, 0.5 + std::sin(a) * x + std::cos(a) * y, z);
      }
  }
  for (const Vec3& p : m.points)
    m.scalars.push_back(0.5 + 0.3 * std::sin(2 * p.x()) * std::cos(p.y()) + 0.25 * p.z() + 0.2 * p.x() * p.y() * p.z());
  const auto id = [np](int i, int j, int k) { return static_cast<std::int32_t>(i + np * (j + np * k)); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        for (auto p : {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                       id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)})
          m.connectivity.push_back(p);
        m.types.push_back(MeshCellType::hexahedron);
        m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
      }
  m.structured = std::array<int, 3>{np, np, np};
  return m;
}

std::vector<ViewRay> bench_rays() {
  std::vector<ViewRay> rays;
  const Vec3 d = Vec3(0.3, 0.2, 1.0).normalized();
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i)
      rays.push_back({Vec3(0.05 + 0.9 * (i + 0.5) / 16 - 0.15, 0.05 + 0.9 * (j + 0.5) / 16 - 0.1, -0.5), d});
  return rays;
}

void BM_mesh_own(benchmark::State& state) {
  const TransferFunctions tf = test::breakpoint_tf();
  const CellTraversal mesh(twisted_grid(12, static_cast<double>(state.range(0))), "bench");
  const LinearCellIntegrator integrator(tf);
  const std::vector<ViewRay> rays = bench_rays();
  CellTrace trace;
  long chords = 0, failed = 0;
  for (auto _ : state) {
    double sum = 0.0;
    for (const ViewRay& r : rays) {
      mesh.trace(r, trace);
      const CellRayResult res = mesh.integrate(trace, integrator, Rgb{0, 0, 0});
      chords += res.chords;
      failed += res.converged ? 0 : 1;
      sum += res.intensity[0];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["chords_per_ray"] = static_cast<double>(chords) / static_cast<double>(state.iterations() * 256);
  state.counters["failed_rays"] = static_cast<double>(failed);
}
BENCHMARK(BM_mesh_own)->Name("BM_mesh/own")->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_mesh_own)->Name("BM_mesh/own_box")->Arg(0)->Unit(benchmark::kMillisecond);

// The traversal alone (chords found, not integrated): its share of BM_mesh/own.
void BM_mesh_own_trace(benchmark::State& state) {
  const CellTraversal mesh(twisted_grid(12, static_cast<double>(state.range(0))), "bench");
  const std::vector<ViewRay> rays = bench_rays();
  CellTrace trace;
  for (auto _ : state) {
    std::size_t n = 0;
    for (const ViewRay& r : rays) {
      mesh.trace(r, trace);
      n += trace.chords.size();
    }
    benchmark::DoNotOptimize(n);
  }
}
BENCHMARK(BM_mesh_own_trace)->Name("BM_mesh/own_trace_only")->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_mesh_own_trace)->Name("BM_mesh/own_box_trace_only")->Arg(0)->Unit(benchmark::kMillisecond);

void BM_mesh_split(benchmark::State& state) {
  const TransferFunctions tf = test::breakpoint_tf();
  const TetTraversal mesh(split_cells(twisted_grid(12, static_cast<double>(state.range(0)))), "bench");
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  const std::vector<ViewRay> rays = bench_rays();
  RayTrace trace;
  Ray ray;
  long segments = 0;
  for (auto _ : state) {
    double sum = 0.0;
    for (const ViewRay& r : rays) {
      mesh.trace(r, trace);
      ray_from_trace(trace, Rgb{0, 0, 0}, ray);
      segments += static_cast<long>(ray.segments.size());
      sum += exact->integrate(ray, nullptr).intensity[0];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["segments_per_ray"] = static_cast<double>(segments) / static_cast<double>(state.iterations() * 256);
}
BENCHMARK(BM_mesh_split)->Name("BM_mesh/split")->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_mesh_split)->Name("BM_mesh/split_box")->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
