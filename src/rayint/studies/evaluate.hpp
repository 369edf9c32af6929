#pragma once
// Runs methods on a case's rays, measures their error against the 50-digit reference and their
// cost per ray. Returns plain structs; report/evaluation_json turns them into JSON.
#include <optional>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint {

struct EvalOptions {
  double timing_batch_seconds = 1e-3;  // each timing batch repeats the ray until this long
  int timing_batches = 5;              // seconds_per_ray is the median over batches
  bool measure_time = true;
  unsigned threads = 0;                // for the reference; 0 = all cores
};

struct MethodOutcome {
  std::string method;  // spec label, e.g. "riemann:n=64"
  RayResult result;
  Diagnostics diagnostics;
  Rgb abs_error{}, rel_error{}, ulp_error{};  // of intensity, per channel
  Rgb transmittance_rel_error{};
  double seconds_per_ray = 0.0;
  bool finite = true;  // all intensities and transmittances finite
  std::string failure;  // non-empty if the method threw (message)
};

struct RayEvaluation {
  ReferenceRay reference;
  std::vector<MethodOutcome> methods;
};

struct CaseEvaluation {
  std::string name, description, source;
  std::vector<RayEvaluation> rays;
  std::optional<TetRepairs> mesh_repairs;  // a mesh case: what reading its mesh repaired (set by the caller)
};

// Fills the error fields of `outcome` from its result against `ref`.
void score_against_reference(MethodOutcome& outcome, const ReferenceRay& ref);

// Median (core/statistics.hpp) over the batches of the seconds per call of integrator.integrate(ray) (no diagnostics, no reference in loop).
double time_per_ray(const RayIntegrator& integrator, const Ray& ray, const EvalOptions& opt);

// References for all rays, computed in parallel over `threads` threads (0: all cores).
std::vector<ReferenceRay> reference_rays(const Case& c, unsigned threads);

CaseEvaluation evaluate_case(const Case& c, const std::vector<MethodSpec>& methods,
                             const EvalOptions& opt);

}  // namespace rayint
