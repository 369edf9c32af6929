#pragma once
// Gradients of the ray integral per method against the 50-digit reference gradient (`rayint
// grad`, issue 28), and the check of a renderer's gradients against the exact ones (`rayint
// gradcheck`). The library computes; report/grad_json.* writes the JSON, cli/ formats.
//
// Methods with a gradient: exact (integrators/exact_grad.hpp, analytic); riemann with n per
// segment and correction=exp, nerf and pl_nerf (integrators/riemann_grad.hpp, the derivative of
// their discrete sums, what autodiff through such a renderer computes); psi_table
// (integrators/psi_table_grad.hpp) and preintegrated (PreintegratedIntegrator::gradient,
// integrators/preintegrated_grad.cpp; the table is built once per case). Any other method is
// reported as failed ("no gradient"), never as a number.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/model/ray.hpp"
#include "rayint/model/preset_point_gradient.hpp"
#include "rayint/model/ray_gradient.hpp"
#include "rayint/reference/reference_grad.hpp"

namespace rayint {

// The gradient of `spec` on `ray`; throws std::invalid_argument for a method without one.
RayGradient method_gradient(const MethodSpec& spec, const TransferFunctions& tf, const Ray& ray);
// Whether method_gradient supports `spec` (names only: exact, riemann, nerf, pl_nerf, psi_table,
// preintegrated).
bool has_gradient(const MethodSpec& spec);

// max over channel c's entries of |got - want| / (largest |want| entry of channel c); NaN if
// either has a NaN entry or the shapes differ, except entries that do not exist (`want.undefined`
// non-empty, want NaN), which must be NaN in `got` too and are skipped. A channel whose reference
// is all zero uses 1.
double gradient_relative_error(const RayGradient& got, const RayGradient& want, int c);

struct GradMethodResult {
  std::string label;
  bool ok = false;
  std::string error;               // why it failed (ok == false)
  RayGradient gradient;
  Rgb error_vs_reference{};        // gradient_relative_error(gradient, reference), per channel
  Rgb error_vs_exact{};            // gradient_relative_error(gradient, exact), per channel
  Rgb intensity_error{};           // |I - I_ref| / |I_ref| (absolute where I_ref == 0)
  // With respect to the ParaView preset's own points (set by the CLI for a preset case).
  std::optional<PresetPointGradient> preset;
};

struct GradRayResult {
  std::optional<ReferenceGradient> reference;
  RayGradient exact;
  std::vector<GradMethodResult> methods;
  std::optional<PresetPointGradient> reference_preset;  // the reference gradient's, likewise
};

struct GradCaseResult {
  std::string name;
  std::string source;
  std::string transfer_origin;  // "" or the ParaView preset the nodes were imported from (set by the CLI)
  std::vector<GradRayResult> rays;
};

struct GradStudyOptions {
  std::vector<MethodSpec> methods;  // default: exact
  bool reference = true;            // compute the 50-digit reference gradient
  unsigned threads = 1;
};

GradCaseResult grad_case(const Case& c, const GradStudyOptions& options);

// --- gradcheck ----------------------------------------------------------------------------

struct GradCandidate {
  std::string source;  // file, for messages
  std::string case_name;
  std::string renderer;
  std::vector<RayGradient> rays;  // shaped like the case (checked by the reader)
};

struct GradCheckEntry {
  std::size_t ray = 0;
  int channel = 0;
  std::string block;      // background, length, scalar_far, scalar_exit, density, color
  std::size_t index = 0;  // segment or node
  std::string parameter;  // position / value for nodes
  double got = 0.0, exact = 0.0, allowed = 0.0;
  double excess = 0.0;    // |got - exact| / allowed; > 1 fails (NaN: a non-finite value)
};

// What a candidate is checked against: the analytic exact gradient (exact_ray_gradient; fast), or
// the 50-digit reference gradient (reference/reference_grad.hpp; slow on long rays, and the truth
// where the analytic one loses digits: an ill-conditioned entry, docs/gradients.md "Accuracy").
enum class GradCheckAgainst { exact, reference };

struct GradCheckOptions {
  double rel_tol = 1e-6, abs_tol = 0.0;
  GradCheckAgainst against = GradCheckAgainst::exact;
  unsigned threads = 1;  // the reference gradient's (0: all cores)
};

struct GradCheckResult {
  std::string case_name;
  std::string renderer;
  GradCheckAgainst against = GradCheckAgainst::exact;
  double rel_tol = 0.0, abs_tol = 0.0;
  // Against the reference: per channel, the largest over the rays of the analytic exact
  // gradient's own distance from it (gradient_relative_error): how far `gradcheck` without
  // --reference would have been from the truth on this case. NaN against exact.
  Rgb exact_vs_reference{std::nan(""), std::nan(""), std::nan("")};
  std::size_t entries = 0, failed = 0;  // failed includes null_in_candidate
  // Entries the candidate gave as null (it cannot give them; NaN in GradCandidate) where the
  // exact derivative exists: not passed, counted in failed; the first is named.
  std::size_t null_in_candidate = 0;
  std::optional<GradCheckEntry> first_null;
  std::size_t undefined = 0;  // entries whose exact derivative does not exist (at a jump): skipped, not passed
  std::string undefined_reason;  // the first such ray's RayGradient::undefined
  std::vector<Rgb> channel_scale;  // [ray][c]: the largest |exact| entry
  std::optional<GradCheckEntry> worst;  // the numeric entry with the largest excess
  bool passed() const { return failed == 0; }
};

// Pass rule per entry: |got - want| <= max(abs_tol, rel_tol * channel_scale), want the exact or
// the reference gradient's entry (options.against) and channel_scale its channel's largest |entry|;
// a null (NaN) got fails (null_in_candidate). Where the derivative does not exist (NaN with
// RayGradient::undefined) the entry is skipped whatever the candidate gives (undefined): neither
// passed nor failed. GradCheckEntry::exact holds `want`.
GradCheckResult grad_check(const Case& c, const GradCandidate& candidate, const GradCheckOptions& options);

}  // namespace rayint
