#pragma once
// Runs methods on a case's rays, measures their error against the 50-digit reference and their
// cost per ray. Returns plain structs; report/evaluation_json turns them into JSON.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint {

// Where evaluate_case is, for a progress line: the reference (segments of the case done / all),
// then each method on each ray (rays done / all, the method's label).
struct EvalProgress {
  enum class Stage { reference, methods } stage = Stage::reference;
  std::size_t done = 0, total = 0;
  std::string method;  // methods: the one about to run
};

struct EvalOptions {
  double timing_batch_seconds = 1e-3;  // each timing batch repeats the ray until this long
  int timing_batches = 5;              // seconds_per_ray is the median over batches
  bool measure_time = true;
  unsigned threads = 0;                // for the reference; 0 = all cores
  bool with_reference = true;          // false: no 50-digit reference, no error fields
  // Called on the calling thread: after each block of reference segments (ReferenceRun), every
  // `progress_seconds` while rays are referenced in parallel, and before each method on each ray.
  std::function<void(const EvalProgress&)> progress;
  double progress_seconds = 1.0;
};

// One method on one ray. A method that threw (not applicable to the case, did not converge) or
// returned a non-finite intensity or transmittance has failed: `failure` says why, and its
// result, errors and time are not numbers (NaN here, null in JSON) -- never an error of 0.
struct MethodOutcome {
  std::string method;  // spec label as typed, e.g. "nerf:n=64:at=near"
  RayResult result;
  Diagnostics diagnostics;
  Rgb abs_error{}, rel_error{}, ulp_error{};  // of intensity, per channel
  Rgb transmittance_rel_error{};
  double seconds_per_ray = 0.0;
  bool finite = true;  // all intensities and transmittances finite
  std::string failure;  // why the method failed on this ray; empty if it did not
  bool failed() const { return !failure.empty(); }
};

// Marks `o` failed with `why` and makes every number in it NaN, so nothing downstream can read a
// failure as a value.
void mark_failed(MethodOutcome& o, const std::string& why);


struct RayEvaluation {
  ReferenceRay reference;  // all zero when the case was evaluated without it
  std::vector<MethodOutcome> methods;
};

struct CaseEvaluation {
  std::string name, description, source;
  std::vector<RayEvaluation> rays;
  bool with_reference = true;  // false: reference and error fields were not computed
  std::optional<TetRepairs> mesh_repairs;  // a mesh case: what reading its mesh repaired (set by the caller)
};

// One method over a case's rays: how many rays, how many failed (and the first failure), and the
// largest errors over the rays that did not fail (NaN when none was scored).
struct MethodSummary {
  std::string method;
  std::size_t rays = 0, failed = 0;
  std::string first_failure;  // "ray I: message"
  double max_rel_error = 0.0, max_ulp_error = 0.0;
  double mean_seconds_per_ray = 0.0;  // over the rays that did not fail
};
std::vector<MethodSummary> summarise_methods(const CaseEvaluation& c);
// Rays on which some method failed, over all cases.
std::size_t failed_outcomes(const std::vector<CaseEvaluation>& cases);

// Fills the error fields of `outcome` from its result against `ref`.
void score_against_reference(MethodOutcome& outcome, const ReferenceRay& ref);

// Median (core/statistics.hpp) over the batches of the seconds per call of integrator.integrate(ray) (no diagnostics, no reference in loop).
double time_per_ray(const RayIntegrator& integrator, const Ray& ray, const EvalOptions& opt);

// References for all rays, computed in parallel over `threads` threads (0: all cores): over the
// rays when there are at least as many as threads, else over the segments of each ray in turn
// (ReferenceRun); the results are the same either way. progress(done, total) counts segments.
std::vector<ReferenceRay> reference_rays(
    const Case& c, unsigned threads,
    const std::function<void(std::size_t done, std::size_t total)>& progress = {},
    double progress_seconds = 1.0);

CaseEvaluation evaluate_case(const Case& c, const std::vector<MethodSpec>& methods,
                             const EvalOptions& opt);

}  // namespace rayint
