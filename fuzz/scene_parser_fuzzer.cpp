// libFuzzer target for the scene reader (rayint::parse_scene_text, input/scene_reader.hpp) on
// arbitrary bytes. File references (background images, grid files) resolve in a folder that does
// not exist, so they are refused like any missing file. Run it with
// `RAYINT_FUZZ_TARGET=scene_parser scripts/fuzz.sh`. Findings: a crash, sanitizer report, hang,
// leak or out-of-memory; an exception other than InputError; an InputError that is not one line
// starting "<source>: ".
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"
#include "rayint/input/scene_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

using rayint::fuzz::require;

constexpr const char* kSource = "fuzz-scene.json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)rayint::parse_scene_text(text, kSource, "/nonexistent-rayint-fuzz-dir");
  } catch (const rayint::InputError& e) {
    const std::string what = e.what();
    const std::string prefix = std::string(kSource) + ": ";
    // A missing referenced file is named by its own path.
    require(what.compare(0, prefix.size(), prefix) == 0 || what.rfind("/nonexistent-rayint-fuzz-dir/", 0) == 0);
    require(what.find('\n') == std::string::npos && what.find('\r') == std::string::npos);
  }
  return 0;
}
