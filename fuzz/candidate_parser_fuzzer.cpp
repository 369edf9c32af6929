// libFuzzer target for the candidate parser of `rayint check` (rayint::parse_candidate_text,
// input/candidate_reader.hpp) on arbitrary bytes, followed by the match against a fixed three-ray case.
// Run it with `RAYINT_FUZZ_TARGET=candidate_parser scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted candidate that breaks the format's guarantees (docs/candidate-format.md):
//     non-empty case name, at least one ray, every intensity finite.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "rayint/input/candidate_reader.hpp"
#include "fuzz_checks.hpp"

using rayint::fuzz::require;

namespace {

// What check_candidate_parser leaves to this format: at least one ray, every intensity finite;
// then the match against the three-ray case, one intensity a ray.
void check_candidate(const rayint::Candidate& c) {
  require(!c.intensity.empty());
  for (const rayint::Rgb& I : c.intensity)
    for (double x : I) require(std::isfinite(x));
  static const rayint::Case kCase = rayint::fuzz::fig2_case({1, 1, 1});
  rayint::require_candidate_matches(c, kCase);
  require(c.case_name == kCase.name && c.intensity.size() == kCase.rays.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rayint::fuzz::check_candidate_parser(&rayint::parse_candidate_text, &check_candidate, data, size,
                                              "fuzz-candidate.json");
}
