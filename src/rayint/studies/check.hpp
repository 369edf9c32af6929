#pragma once
// `rayint check`: another renderer's per-ray intensities (a "candidate") against the exact
// emission-absorption integral (Williams & Max 1992, Eq. 4, evaluated by the `exact` method).
//
// Pass rule, per ray and per channel:
//   |got - expected| <= max(abs_tol, rel_tol * |expected|)
// i.e. a channel passes when it is within the absolute OR the relative tolerance. The check
// passes when every channel of every ray passes. `expected` is the `exact` method (~1e-13
// relative, tests/test_exact.cpp); the 50-digit reference is reported beside it, for context,
// as the uncertainty of `expected` itself. The format of candidates and of the diff is in
// docs/candidate-format.md. Returns plain structs; input/candidate_reader turns them into JSON.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "rayint/model/ray.hpp"

namespace rayint {

struct MeshCase;  // mesh/mesh_case.hpp

// Another renderer's answer for one case: one intensity per ray of the case, in its order.
struct Candidate {
  std::string case_name;       // must equal Case::name
  std::string renderer;        // free text, optional
  std::string source;          // file it was read from, for messages and the diff
  std::vector<Rgb> intensity;  // per ray: light reaching the eye, r g b
};

struct CheckOptions {
  double rel_tol = 1e-6;       // relative to |expected|; 1e-6 ~ 8 ulps of a float32 result
  double abs_tol = 0.0;        // absolute; 0 = relative only (expected 0 needs got == 0)
  bool with_reference = true;  // also compute the 50-digit reference (context, not the rule)
  unsigned threads = 0;        // threads for the reference; 0 = all cores
};

struct ChannelCheck {
  double expected = 0.0;   // `exact` method
  double got = 0.0;        // candidate
  double abs_error = 0.0;  // |got - expected|
  double rel_error = 0.0;  // abs_error / |expected|: 0 if equal, +inf if expected == 0 != got
  double allowed = 0.0;    // max(abs_tol, rel_tol * |expected|)
  bool pass = false;       // abs_error <= allowed (false if anything is non-finite)
  // Context, NaN unless CheckOptions::with_reference: the 50-digit reference value (rounded to
  // double) and |expected - reference|, the uncertainty of `expected`.
  double reference = std::numeric_limits<double>::quiet_NaN();
  double expected_error = std::numeric_limits<double>::quiet_NaN();
};

struct RayCheck {
  std::array<ChannelCheck, kChannels> channel{};
  bool pass = false;  // all channels pass
  // Own-interpolation cases (check_candidate_own): why the expected value could not be computed
  // (a chord that did not converge; its channels are then NaN and fail), and why the 50-digit
  // reference could not (context only). Empty: it was.
  std::string expected_failure, reference_failure;
};

struct CheckSummary {
  std::size_t rays = 0, failed_rays = 0;
  std::size_t channels = 0, failed_channels = 0;
  double max_abs_error = 0.0, max_rel_error = 0.0;  // over all rays and channels
  // Worst channel by abs_error / allowed (the first failing one's ray if equal): where to look.
  std::size_t worst_ray = 0;
  int worst_channel = 0;
  // Largest |expected - reference| / |reference| over all channels (NaN without the reference):
  // tolerances below it cannot be judged by this check.
  double expected_max_rel_uncertainty = std::numeric_limits<double>::quiet_NaN();
  // Rays whose expected value failed (counted in failed_rays too) and rays whose reference
  // failed (their channels are left out of expected_max_rel_uncertainty). Always 0 for `exact`.
  std::size_t expected_failed_rays = 0, reference_failed_rays = 0;
};

struct CheckResult {
  std::string case_name, case_source, candidate_source, renderer;
  // What `expected` is: "exact" (the exact method on the case's segments) or "own" (cells other
  // than tetrahedra integrated in their own interpolation, check_candidate_own).
  std::string expected_method = "exact";
  CheckOptions options;
  std::vector<RayCheck> rays;
  CheckSummary summary;
  bool pass = false;
};

// The pass rule above for one channel (exposed for tests and documentation).
bool within_tolerance(double got, double expected, double rel_tol, double abs_tol);

// Compares `candidate` with the exact intensities of `c`. Preconditions (input/candidate_reader and the
// CLI check them on input and report InputErrors): one candidate entry per ray of `c`, and
// finite tolerances >= 0; otherwise throws std::invalid_argument. A non-finite `got` fails.
CheckResult check_candidate(const Case& c, const Candidate& candidate, const CheckOptions& opt);

// The same check on a mesh case of cells other than tetrahedra (MeshCase::cells set, "mode":
// "own"): `expected` is each evaluation ray's intensity integrated in the cells' own interpolation
// in double, and the reference the same chords by the 50-digit cell reference -- both as `rayint
// eval` computes them (studies/own_cells_eval.hpp, evaluate_own_cells). A ray whose integration
// did not converge has NaN expected channels, fails, and says why (RayCheck::expected_failure).
// Same preconditions as check_candidate, with the case's evaluation rays (mesh/mesh_case.hpp).
CheckResult check_candidate_own(const MeshCase& mesh_case, const Candidate& candidate, const CheckOptions& opt);

}  // namespace rayint
