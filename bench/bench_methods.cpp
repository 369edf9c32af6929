// Cost per ray of every method of the registry at the middle setting of its knob (the middle
// entry of the sweep table, src/rayint/studies/sweep.hpp: riemann/rk4 n = 256, ode rtol = 1e-8,
// tables size = 256), on the rays of cases/smooth-convergence.json -- a representative smooth
// case with a few breakpoints inside segments. A method that refuses that case (particle needs a
// single transfer function) runs on cases/paper-figure-2.json instead; the label names the case.
// One iteration integrates one ray (cycling through the case's rays), without diagnostics, so the
// time per iteration is the mean time per ray. Table construction is outside the timed loop.
// Run: build/bench/rayint_bench --benchmark_filter=BM_method --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median)
// Cases are read from <source>/cases (set RAYINT_CASES_DIR to read them elsewhere).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rayint/studies/sweep.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/input/case_reader.hpp"

namespace {

std::string case_path(const std::string& name) {
  const char* dir = std::getenv("RAYINT_CASES_DIR");
  const std::filesystem::path base =
      dir ? std::filesystem::path(dir)
          : std::filesystem::path(__FILE__).parent_path().parent_path() / "cases";
  return (base / (name + ".json")).string();
}

// The representative case first; the fallback for methods that refuse it.
const std::vector<std::string>& bench_cases() {
  static const std::vector<std::string> names = {"smooth-convergence", "paper-figure-2"};
  return names;
}

void BM_method(benchmark::State& state, const rayint::MethodSpec& spec) {
  rayint::Case c;
  std::unique_ptr<rayint::RayIntegrator> integrator;
  std::string why;
  for (const auto& name : bench_cases()) {
    try {
      c = rayint::read_case_file(case_path(name));
      integrator = rayint::make_integrator(spec, c.transfer);
      break;
    } catch (const std::exception& e) {
      why += std::string(why.empty() ? "" : "; ") + e.what();
    }
  }
  if (!integrator) {
    state.SkipWithError(why.c_str());
    return;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const rayint::RayResult r = integrator->integrate(c.rays[i], nullptr);
    benchmark::DoNotOptimize(r.intensity);
    i = (i + 1) % c.rays.size();
  }
  state.SetLabel(spec.label() + " on " + c.name + " (time per ray)");
  state.SetItemsProcessed(state.iterations());
}

const bool registered = [] {
  for (const rayint::SweepAxis& axis : rayint::sweep_table()) {
    const std::vector<rayint::MethodSpec> specs = axis.settings();
    const rayint::MethodSpec& middle = specs[specs.size() / 2];
    benchmark::RegisterBenchmark(("BM_method/" + middle.label()).c_str(), BM_method, middle);
  }
  return true;
}();

}  // namespace
