#pragma once
// Published plane-parallel benchmark values (the DISORT test problems 1 and 3, after van de Hulst
// 1980; file format of cases/scattering/disort_slab.json) and their check against the two slab
// solvers.
//
// Tolerances (what the file states): 1e-4 relative for every value, 1e-3 relative for the
// fluxes of thin slabs (tau < 0.1), whose published values carry DISORT's quadrature error.
// Acceptance:
// - doubling (deterministic): |ours - published| <= tol |published|.
// - Monte Carlo: |ours - published| <= max(tol |published|, 4 SE), and 4 SE <= mc_max_rel
//   |published| (default 2%), so a run with too few photons cannot pass by having a wide interval;
//   the 95% interval (mean +- 1.96 SE) covering the published value is reported beside it.
//   4 SE: the chance that an unbiased estimate fails is 6e-5 per value (normal tails), and with
//   a fixed seed the outcome is reproducible.
// Verdict per value (both methods run):
// - reproduced: both checks above hold;
// - disputed: the doubling value misses the tolerance, but the two independent solvers agree
//   with each other (|doubling - MC| <= 4 SE), the Monte Carlo rejects the published value
//   (|published - MC| > 4 SE) and 4 SE <= mc_max_rel |published|: evidence that the published
//   value is off, not us. Too few photons make a value "failed", never "disputed".
//   For isotropic problems the integral equation for the source function
//   (slab_integral_equation.hpp) is a third, deterministic solver: a value is also disputed when
//   the doubling misses the tolerance, the integral equation agrees with the doubling within
//   max(4 x its error estimate, 1e-6 |published|) with an error estimate <= 1e-6 |published|,
//   so it excludes the published value too, and the Monte Carlo (if run) agrees with the
//   doubling within 4 SE.
// - failed: anything else. With one method only, a value is reproduced or failed.
#include <functional>
#include <string>
#include <vector>

#include "rayint/scattering/slab.hpp"
#include "rayint/scattering/slab_doubling.hpp"
#include "rayint/scattering/slab_integral_equation.hpp"
#include "rayint/scattering/slab_monte_carlo.hpp"
#include "rayint/scattering/pn.hpp"

namespace rayint {

enum class SlabQuantity { flux_up_top, diffuse_down_bottom, direct_down_bottom, intensity_up_top,
                          intensity_down_bottom };
const char* quantity_name(SlabQuantity q);

struct BenchmarkValue {
  SlabQuantity quantity;
  double mu = 0;  // detector cosine, for intensities
  std::size_t detector = 0;  // index into mu_up / mu_down
  double published = 0;
  double tolerance_rel = 1e-4;
  std::string label() const;  // "flux_up_top" or "intensity_up_top(mu=0.5)"
};

struct BenchmarkProblem {
  std::string id;
  SlabProblem problem;
  std::vector<BenchmarkValue> values;
};

struct SlabBenchmark {
  std::string source;  // the file's "source" text
  std::vector<BenchmarkProblem> problems;
};

// Reads and validates a benchmark file (strict: unknown fields, bad numbers -> InputError).

struct BenchmarkRow {
  std::string problem_id;
  BenchmarkValue value;
  bool has_doubling = false;
  double doubling = 0, doubling_rel_dev = 0;
  bool doubling_pass = false;
  bool has_integral_equation = false;  // isotropic problems only
  double integral_equation = 0, ie_error = 0, ie_order = 0, ie_rel_dev = 0;
  bool ie_pass = false;
  bool has_monte_carlo = false;
  Estimate monte_carlo;
  double mc_rel_dev = 0;
  double mc_allowed = 0;   // max(tol |published|, 4 SE)
  bool mc_in_95 = false;
  bool mc_pass = false;    // the acceptance rule above
  enum class Verdict { reproduced, disputed, failed } verdict = Verdict::failed;
  const char* verdict_name() const;
};

struct BenchmarkRunOptions {
  bool doubling = true;
  bool monte_carlo = true;
  bool integral_equation = true;  // on the isotropic problems
  bool pn = false;                 // P_N (pn.hpp); one problem or a slab scene only
  PnOptions pn_options;
  DoublingOptions doubling_options;
  SlabIntegralEquationOptions ie_options;
  SlabMonteCarloOptions mc_options;
  double mc_max_rel = 0.02;  // 4 SE must be within this fraction of the published value
  bool mc_split = true;      // exact orders 0-1 + Monte Carlo orders >= 2 (else plain Monte Carlo)
};

struct BenchmarkProblemCost {
  std::string problem_id;
  double doubling_seconds = 0;
  double ie_seconds = 0;
  int ie_segments = 0;  // finest mesh; 0 if not run
  double mc_seconds = 0;
  long long mc_photons = 0, mc_collisions = 0;
};

struct BenchmarkReport {
  std::vector<BenchmarkRow> rows;
  std::vector<BenchmarkProblemCost> costs;
  bool all_pass() const;  // no value failed (disputed values are reported, not failed)
};

// `progress(problem_id)` (may be empty) is called before each problem.
BenchmarkReport run_slab_benchmark(const SlabBenchmark& benchmark, const BenchmarkRunOptions& options,
                                   const std::function<void(const std::string&)>& progress = {});

}  // namespace rayint
