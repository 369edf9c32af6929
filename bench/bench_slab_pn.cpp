// Cost per solve of the plane-parallel slab by P_N (src/rayint/scattering/pn.hpp) at each order,
// beside the adding-doubling solver (64 streams, the slab reference), on two DISORT problems
// (cases/scattering/disort_slab.json): 1e (isotropic, tau 32, omega 1, beam mu0 0.1) and 3a
// (Henyey-Greenstein g 0.75, tau 1, omega 1, mu0 1), three detector cosines each way. One
// iteration is one whole solve (eigen-decomposition, boundary system, source-function
// integration at the detectors).
// Run: build/bench/rayint_bench --benchmark_filter='BM_slab_' --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median)
#include <benchmark/benchmark.h>

#include "rayint/scattering/pn.hpp"
#include "rayint/scattering/slab_doubling.hpp"

namespace {

rayint::SlabProblem problem(int which) {
  rayint::SlabProblem p;
  p.mu_up = {0.1, 0.5, 1.0};
  p.mu_down = {0.1, 0.5, 1.0};
  if (which == 0) {  // 1e
    p.tau = 32;
    p.albedo = 1;
    p.mu0 = 0.1;
  } else {  // 3a
    p.tau = 1;
    p.albedo = 1;
    p.mu0 = 1;
    p.phase = rayint::PhaseFunction::henyey_greenstein(0.75);
  }
  return p;
}

void BM_slab_pn(benchmark::State& state) {
  const rayint::SlabProblem p = problem(static_cast<int>(state.range(0)));
  rayint::PnOptions o;
  o.order = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(rayint::solve_slab_pn(p, o));
  state.SetLabel(state.range(0) == 0 ? "1e" : "3a");
}
BENCHMARK(BM_slab_pn)
    ->ArgsProduct({{0, 1}, {1, 3, 7, 15, 31, 63, 127}})
    ->Unit(benchmark::kMicrosecond);

void BM_slab_doubling(benchmark::State& state) {
  const rayint::SlabProblem p = problem(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(rayint::solve_slab_doubling(p));
  state.SetLabel(state.range(0) == 0 ? "1e" : "3a");
}
BENCHMARK(BM_slab_doubling)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
