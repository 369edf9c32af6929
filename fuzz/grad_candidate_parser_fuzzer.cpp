// libFuzzer target for the candidate-gradient parser of `rayint gradcheck`
// (rayint::parse_grad_candidate_text, input/grad_candidate_reader.hpp) on arbitrary bytes,
// followed by the match against a fixed case (paper-figure-2's shape: 3 rays of 1, 2, 1
// segments; density 2 nodes, colours 2 nodes). Run it with
// `RAYINT_FUZZ_TARGET=grad_candidate_parser scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted candidate that breaks the format's guarantees (docs/gradients.md): non-empty
//     case name, at least one ray, every entry finite, scalar and length blocks of one size;
//     after the match, every block shaped like the case.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/input/grad_candidate_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::check_message;
using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-grad-candidate.json";

rayint::Case fig2_shape() {
  rayint::Case c;
  c.name = "fig2";
  c.source = "fig2.json";
  for (int ch = 0; ch < rayint::kChannels; ++ch) {
    c.transfer.density[ch] = {{0.0, 1.0}, {5.0, 2.0}};
    c.transfer.color[ch] = {{0.0, 1.0}, {1.0, 1.0}};
  }
  c.rays.resize(3);
  c.rays[0].segments.resize(1);
  c.rays[1].segments.resize(2);
  c.rays[2].segments.resize(1);
  return c;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const rayint::Case kCase = fig2_shape();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const rayint::GradCandidate c = rayint::parse_grad_candidate_text(text, kSource);
    require(!c.case_name.empty() && !c.rays.empty() && c.source == kSource);
    for (const rayint::RayGradient& g : c.rays) {
      require(g.length.size() == g.scalar_far.size() && g.length.size() == g.scalar_exit.size());
      for (int ch = 0; ch < rayint::kChannels; ++ch)
        g.for_each(ch, [](double v, const char*, std::size_t, const char*) { require(std::isfinite(v)); });
    }
    rayint::require_grad_candidate_matches(c, kCase);
    require(c.rays.size() == kCase.rays.size());
    for (std::size_t i = 0; i < c.rays.size(); ++i) {
      require(c.rays[i].length.size() == kCase.rays[i].segments.size());
      for (int ch = 0; ch < rayint::kChannels; ++ch)
        require(c.rays[i].density[ch].size() == 2 && c.rays[i].color[ch].size() == 2);
    }
  } catch (const rayint::InputError& e) {
    check_message(e.what(), kSource);
  }
  return 0;
}
