// libFuzzer target for the case parser (rayint::parse_case_text, input/case_reader.hpp) on arbitrary
// bytes. Built by fuzz/CMakeLists.txt with -fsanitize=fuzzer,address,undefined; run it with
// scripts/fuzz.sh. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping the parser (libFuzzer reports the
//     uncaught exception as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - a case accepted although it breaks the format's guarantees (cases/README.md): non-empty
//     name, at least one ray and one segment, lengths and values finite and >= 0, scalars finite,
//     breakpoints non-decreasing, a scalar at most twice in a row (a jump);
//   - the streaming reader (parse_case_text) and the whole-tree walk
//     (detail::parse_case_text_tree) disagreeing: another message, or other rays.
// Each check traps, so the input is saved as a crash artifact.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "rayint/input/case_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::check_message;
using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-input.json";

bool finite_non_negative(double x) { return std::isfinite(x) && x >= 0.0; }

void check_function(const rayint::PiecewiseLinear& f) {
  require(!f.scalar.empty() && f.scalar.size() == f.value.size());
  for (std::size_t i = 0; i < f.scalar.size(); ++i) {
    require(std::isfinite(f.scalar[i]) && finite_non_negative(f.value[i]));
    if (i > 0) require(f.scalar[i] >= f.scalar[i - 1]);
    if (i > 1) require(f.scalar[i] > f.scalar[i - 2]);
  }
}

void check_case(const rayint::Case& c) {
  require(!c.name.empty() && c.source == kSource && !c.rays.empty());
  for (int k = 0; k < rayint::kChannels; ++k) {
    check_function(c.transfer.density[k]);
    check_function(c.transfer.color[k]);
  }
  for (const rayint::Ray& ray : c.rays) {
    // No segment requirement: a mesh case's ray that misses the mesh has none (background only;
    // cases/mesh-inline-cube.json has one), which this check, older than mesh cases, refused.
    // The readers' own refusal of an empty "segments" array is tested in tests/test_case_reader.cpp.
    for (double b : ray.background) require(finite_non_negative(b));
    for (const rayint::Segment& s : ray.segments)
      require(finite_non_negative(s.length) && std::isfinite(s.scalar_far) &&
              std::isfinite(s.scalar_exit));
  }
}

void check_same_rays(const rayint::Case& a, const rayint::Case& b) {
  require(a.rays.size() == b.rays.size());
  for (std::size_t i = 0; i < a.rays.size(); ++i) {
    require(a.rays[i].background == b.rays[i].background);
    require(a.rays[i].segments.size() == b.rays[i].segments.size());
    for (std::size_t k = 0; k < a.rays[i].segments.size(); ++k)
      require(std::memcmp(&a.rays[i].segments[k], &b.rays[i].segments[k], sizeof(rayint::Segment)) == 0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  rayint::Case streamed, tree;
  std::string streamed_error, tree_error;
  try {
    streamed = rayint::parse_case_text(text, kSource);
    check_case(streamed);
  } catch (const rayint::InputError& e) {
    streamed_error = e.what();
    check_message(streamed_error, kSource);
  }
  try {
    tree = rayint::detail::parse_case_text_tree(text, kSource);
  } catch (const rayint::InputError& e) {
    tree_error = e.what();
  }
  require(streamed_error == tree_error);
  if (streamed_error.empty()) check_same_rays(streamed, tree);
  return 0;
}
