// Cost of one cell of a ray in the linear cells' own interpolation (cells/linear_cells.hpp,
// cells/cell_integral.hpp), single-threaded, per cell (chord() + LinearCellIntegrator::integrate), over
// 256 random distorted cells each with one ray through a random interior point (the families
// and transfer functions of tools/cell_accuracy.cpp, edge 1, 10-30 % perturbation):
//   BM_cell/hexahedron     a distorted hexahedron, isoparametric path (Newton + Chebyshev + GK);
//   BM_cell/hex_as_5_tets  the same hexahedron split into 5 tetrahedra (the structured split
//                          {0,1,3,4} {1,2,3,6} {1,4,5,6} {3,4,6,7} {1,3,4,6}), each tetra's chord
//                          + exact closed form: what a tet-split mesh pays for the same volume;
//   BM_cell/wedge, BM_cell/pyramid   distorted wedges and pyramids, isoparametric path;
//   BM_cell/parallelepiped an affine hexahedron (polynomial path, no Newton);
//   BM_cell/tetra          one tetra (exact closed form).
// The issue-29 target is a hex mesh at <= 3x the time of the same mesh split into tets; the
// ratio hexahedron / hex_as_5_tets is the per-cell part of that (traversal costs excluded).
// Run: build/bench/rayint_bench --benchmark_filter=BM_cell --benchmark_repetitions=3
//      --benchmark_report_aggregates_only=true      (quote the median)
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "cell_samples.hpp"  // tests/: the transfer functions shared with the tests and tools

namespace {

using namespace rayint;

struct Sample {
  std::vector<LinearCell> cells;  // the cell, or its 5 tetrahedra
  ViewRay ray;
};

std::vector<Sample> make_samples(LinearCellType type, bool affine, bool split) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> out;
  while (out.size() < 256) {
    std::vector<Vec3> nodes;
    std::vector<double> values;
    const double amount = affine ? 0.0 : 0.1 + 0.2 * u(rng);
    for (const Vec3& r : linear_reference_nodes(type)) {
      nodes.push_back(r + amount * (2.0 * Vec3(u(rng), u(rng), u(rng)) - Vec3::Ones()) / std::sqrt(3.0));
      values.push_back(u(rng));
    }
    const LinearCell cell = make_linear_cell(type, nodes, values);
    Vec3 p;
    do p = Vec3(u(rng), u(rng), u(rng));
    while (!inside_reference(type, p));
    const Vec3 dir = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    Sample s;
    s.ray = {cell_position(cell, p) - 3.0 * dir, dir};
    if (split) {
      static const int tets[5][4] = {{0, 1, 3, 4}, {1, 2, 3, 6}, {1, 4, 5, 6}, {3, 4, 6, 7}, {1, 3, 4, 6}};
      for (const auto& t : tets) {
        std::vector<Vec3> tn;
        std::vector<double> tv;
        for (int k : t) {
          tn.push_back(nodes[static_cast<std::size_t>(k)]);
          tv.push_back(values[static_cast<std::size_t>(k)]);
        }
        s.cells.push_back(make_linear_cell(LinearCellType::tetra, tn, tv));
      }
    } else {
      s.cells.push_back(cell);
    }
    out.push_back(std::move(s));
  }
  return out;
}

void run(benchmark::State& state, LinearCellType type, bool affine, bool split) {
  const TransferFunctions tf = test::breakpoint_tf();
  const LinearCellIntegrator integrator(tf);
  const std::vector<Sample> samples = make_samples(type, affine, split);
  long chords = 0, failed = 0;
  for (auto _ : state) {
    for (const Sample& s : samples)
      for (const LinearCell& cell : s.cells) {
        const Chord ch = chord(cell, s.ray);
        for (const ChordInterval& iv : ch.intervals) {
          const CellPieceIntegral r = integrator.integrate(cell, s.ray, iv.t_near, iv.t_far);
          benchmark::DoNotOptimize(r.emission);
          ++chords;
          failed += r.converged ? 0 : 1;
        }
      }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(samples.size()));  // items = cells of the original mesh
  state.counters["chords_per_cell"] = static_cast<double>(chords) / static_cast<double>(state.iterations() * samples.size());
  state.counters["failed"] = static_cast<double>(failed);
}

void BM_cell(benchmark::State& state, LinearCellType type, bool affine, bool split) { run(state, type, affine, split); }

BENCHMARK_CAPTURE(BM_cell, hexahedron, LinearCellType::hexahedron, false, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_cell, hex_as_5_tets, LinearCellType::hexahedron, false, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_cell, wedge, LinearCellType::wedge, false, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_cell, pyramid, LinearCellType::pyramid, false, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_cell, parallelepiped, LinearCellType::hexahedron, true, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_cell, tetra, LinearCellType::tetra, false, false)->Unit(benchmark::kMicrosecond);

}  // namespace
