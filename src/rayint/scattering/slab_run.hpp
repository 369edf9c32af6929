#pragma once
// One plane-parallel slab problem solved by the methods asked for (what `rayint slab` runs on
// one problem or a slab scene), and the bookkeeping of a benchmark run (slab_benchmark.hpp):
// selecting problems by id, and the verdict counts and summed costs of a report.
#include <optional>
#include <string>
#include <vector>

#include "rayint/scattering/slab_benchmark.hpp"

namespace rayint {

// The methods and their knobs are those of a benchmark run (slab_benchmark.hpp); besides,
// options.mc_options.max_order 1 runs single scattering only, by Monte Carlo and in closed form.
// The doubling and the integral equation run only without a max_order; the integral equation on
// isotropic problems when options.integral_equation (the CLI sets it only with the doubling);
// P_N when options.pn, without a max_order. A ground albedo > 0 (Lambertian ground): doubling,
// P_N and the analog Monte Carlo (not the split one); no integral equation, no max_order (throws).
// run_slab_benchmark solves every problem through this one dispatch.
struct SlabRun {
  BenchmarkRunOptions options;
  std::optional<SlabValues> doubling;
  double doubling_seconds = 0;  // wall time of the doubling solve
  std::optional<SlabIntegralEquationResult> integral_equation;
  std::optional<SlabValues> single_scattering_closed_form;  // max_order 1
  std::optional<PnSolution> pn;  // options.pn, without a max_order
  double pn_seconds = 0;         // wall time of the P_N solve
  std::optional<SlabEstimates> monte_carlo;
  bool mc_split = false;  // the Monte Carlo estimator that ran
};

SlabRun run_slab_problem(const SlabProblem& problem, const BenchmarkRunOptions& options);

// Keeps the problems named in `ids`, in that order; an id not in the benchmark throws
// std::invalid_argument "no problem 'ID' in <source_name>".
void select_benchmark_problems(SlabBenchmark& benchmark, const std::vector<std::string>& ids,
                               const std::string& source_name);

struct BenchmarkTotals {
  int reproduced = 0, disputed = 0, failed = 0;
  long long mc_photons = 0, mc_collisions = 0;
  double mc_seconds = 0, doubling_seconds = 0, ie_seconds = 0;
  int ie_finest_segments = 0;  // the largest over the problems; 0 if the integral equation never ran
};

BenchmarkTotals benchmark_totals(const BenchmarkReport& report);

}  // namespace rayint
