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

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz-scene.json", folder = "/nonexistent-rayint-fuzz-dir";
  // A missing referenced file is named by its own path.
  return rayint::fuzz::refusals_start_with({source + ": ", folder + "/"},
                                           [&] { (void)rayint::parse_scene_text(text, source, folder); });
}
