// libFuzzer target for the candidate-gradient parser of `rayint gradcheck`
// (rayint::parse_grad_candidate_text, input/grad_candidate_reader.hpp) on arbitrary bytes,
// followed by the match against a fixed case (paper-figure-2's shape: 3 rays of 1, 2, 1
// segments; density 2 nodes, colours 2 nodes). Run it with
// `RAYINT_FUZZ_TARGET=grad_candidate_parser scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted candidate that breaks the format's guarantees (docs/gradients.md): non-empty
//     case name, at least one ray, every entry finite or NaN (null: an entry the renderer cannot
//     give), scalar and length blocks of one size;
//     after the match, every block shaped like the case.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "rayint/input/candidate_reader.hpp"
#include "fuzz_checks.hpp"

using rayint::fuzz::require;

namespace {

// What check_candidate_parser leaves to this format: at least one ray, every entry finite or
// NaN, scalar and length blocks of one size; then the match against the case, every block
// shaped like it.
void check_grad_candidate(const rayint::GradCandidate& c) {
  require(!c.rays.empty());
  for (const rayint::RayGradient& g : c.rays) {
    require(g.length.size() == g.scalar_far.size() && g.length.size() == g.scalar_exit.size());
    for (int ch = 0; ch < rayint::kChannels; ++ch)
      g.for_each(ch, [](double v, const char*, std::size_t, const char*) { require(std::isfinite(v) || std::isnan(v)); });
  }
  static const rayint::Case kCase = rayint::fuzz::fig2_case({1, 2, 1});
  rayint::require_grad_candidate_matches(c, kCase);
  require(c.rays.size() == kCase.rays.size());
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    require(c.rays[i].length.size() == kCase.rays[i].segments.size());
    for (int ch = 0; ch < rayint::kChannels; ++ch)
      require(c.rays[i].density[ch].size() == 2 && c.rays[i].color[ch].size() == 2);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rayint::fuzz::check_candidate_parser(&rayint::parse_grad_candidate_text, &check_grad_candidate, data, size,
                                              "fuzz-grad-candidate.json");
}
