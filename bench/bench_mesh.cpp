// Cost of the mesh path on cases/mesh-ball-100k.json (105,456 tets, 12,288 boundary faces), per
// ray, single-threaded, over 4,096 rays of its camera (every 8th pixel of the 512x512 image):
//   BM_mesh_first_hit_embree  Embree's first hit on the boundary faces (what traversal uses);
//   BM_mesh_first_hit_scan    the same first hit by scanning every boundary face (double
//                             Moller-Trumbore): the baseline an acceleration structure must beat;
//   BM_mesh_trace             the whole traversal (first hits, cell walk, star searches, Eq. 13);
//   BM_mesh_exact             `exact` on the traced segments (the integration share);
//   BM_mesh_piece_splitter    PieceSplitter::append on the traced segments (the splitting part
//                             of `exact`), counter segments/s; shared_ends is the fraction of
//                             neighbouring segments whose shared end has the same scalar bits
//                             from both cells (where one evaluation could serve both);
//   BM_mesh_piece_splitter_grey the per-ray PieceSplitter::append into GreyPieceColumns (what
//                             the exact render's grey batch calls), counter segments/s.
// Run: build/bench/rayint_bench --benchmark_filter=BM_mesh --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median)
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/first_hit.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/model/pieces.hpp"

namespace {

using namespace rayint;

struct MeshBench {
  MeshCase mc;
  std::unique_ptr<TetTraversal> mesh;
  std::vector<std::array<std::int32_t, 3>> boundary;
  std::unique_ptr<BoundaryFirstHit> embree;
  std::vector<ViewRay> rays;
  std::vector<Ray> traced;
  std::unique_ptr<RayIntegrator> exact;

  MeshBench() {
    const char* dir = std::getenv("RAYINT_CASES_DIR");
    const std::filesystem::path base =
        dir ? std::filesystem::path(dir) : std::filesystem::path(__FILE__).parent_path().parent_path() / "cases";
    mc = read_mesh_case_file((base / "mesh-ball-100k.json").string());
    mesh = std::make_unique<TetTraversal>(mc.mesh, mc.neighbors, mc.mesh_source);
    for (std::size_t f = 0; f < mesh->boundary_face_count(); ++f) boundary.push_back(mesh->boundary_face(f).points);
    embree = std::make_unique<BoundaryFirstHit>(mc.mesh.points, boundary, mesh->box_min(), mesh->box_max());
    for (int y = 0; y < mc.camera->height; y += 8)
      for (int x = 0; x < mc.camera->width; x += 8) rays.push_back(mc.camera->ray_for_pixel(x, y));
    for (const ViewRay& r : rays) traced.push_back(mesh_ray(*mesh, r, mc.background));
    exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  }
  static MeshBench& get() {
    static MeshBench b;
    return b;
  }
};

bool accept_all(const void*, std::uint32_t) { return true; }

void BM_mesh_first_hit_embree(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  std::size_t i = 0;
  for (auto _ : state) {
    const ViewRay& r = b.rays[i++ % b.rays.size()];
    benchmark::DoNotOptimize(b.embree->first(r.origin, r.direction, 0.0, std::numeric_limits<double>::infinity(), accept_all, nullptr));
  }
}
BENCHMARK(BM_mesh_first_hit_embree);

void BM_mesh_first_hit_scan(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  const std::vector<Vec3>& p = b.mc.mesh.points;
  std::size_t i = 0;
  for (auto _ : state) {
    const ViewRay& r = b.rays[i++ % b.rays.size()];
    double best = std::numeric_limits<double>::infinity();
    std::int64_t hit = -1;
    for (std::size_t f = 0; f < b.boundary.size(); ++f) {  // Moller-Trumbore
      const Vec3& a = p[b.boundary[f][0]];
      const Vec3 e1 = p[b.boundary[f][1]] - a, e2 = p[b.boundary[f][2]] - a;
      const Vec3 h = r.direction.cross(e2);
      const double det = e1.dot(h);
      if (det == 0.0) continue;
      const Vec3 s = r.origin - a;
      const double u = s.dot(h) / det;
      if (u < 0.0 || u > 1.0) continue;
      const Vec3 q = s.cross(e1);
      const double v = r.direction.dot(q) / det;
      if (v < 0.0 || u + v > 1.0) continue;
      const double t = e2.dot(q) / det;
      if (t >= 0.0 && t < best) {
        best = t;
        hit = static_cast<std::int64_t>(f);
      }
    }
    benchmark::DoNotOptimize(hit);
  }
}
BENCHMARK(BM_mesh_first_hit_scan);

void BM_mesh_trace(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  RayTrace trace;
  std::size_t i = 0;
  for (auto _ : state) {
    b.mesh->trace(b.rays[i++ % b.rays.size()], trace);
    benchmark::DoNotOptimize(trace.crossings.data());
  }
}
BENCHMARK(BM_mesh_trace);

void BM_mesh_exact(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(b.exact->integrate(b.traced[i++ % b.traced.size()], nullptr));
}
BENCHMARK(BM_mesh_exact);

void BM_mesh_piece_splitter(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  const PieceSplitter splitter(b.mc.transfer);
  std::vector<Piece> pieces;
  std::size_t i = 0;
  long segments = 0;
  for (auto _ : state) {
    const Ray& ray = b.traced[i++ % b.traced.size()];
    pieces.clear();
    for (const Segment& s : ray.segments) splitter.append(s, pieces);
    segments += static_cast<long>(ray.segments.size());
    benchmark::DoNotOptimize(pieces.data());
  }
  state.counters["segments"] = benchmark::Counter(static_cast<double>(segments), benchmark::Counter::kIsRate);
  long pairs = 0, shared = 0;
  for (const Ray& ray : b.traced)
    for (std::size_t k = 0; k + 1 < ray.segments.size(); ++k) {
      ++pairs;
      const double a = ray.segments[k].scalar_exit, c = ray.segments[k + 1].scalar_far;
      shared += std::memcmp(&a, &c, sizeof a) == 0;
    }
  state.counters["shared_ends"] = pairs > 0 ? static_cast<double>(shared) / static_cast<double>(pairs) : 0.0;
}
BENCHMARK(BM_mesh_piece_splitter);

void BM_mesh_piece_splitter_grey(benchmark::State& state) {
  MeshBench& b = MeshBench::get();
  const PieceSplitter splitter(b.mc.transfer);
  GreyPieceColumns columns;
  std::size_t i = 0;
  long segments = 0;
  for (auto _ : state) {
    const Ray& ray = b.traced[i++ % b.traced.size()];
    columns.clear();
    benchmark::DoNotOptimize(splitter.append(ray.segments, columns));
    segments += static_cast<long>(ray.segments.size());
    benchmark::DoNotOptimize(columns.length.data());
  }
  state.counters["segments"] = benchmark::Counter(static_cast<double>(segments), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_mesh_piece_splitter_grey);

}  // namespace
