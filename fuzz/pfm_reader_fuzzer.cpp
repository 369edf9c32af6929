// libFuzzer target for the Portable Float Map reader of `rayint check --candidate-image`
// (rayint::decode_pfm, render/float_image.hpp) on arbitrary bytes. Run it with
// `RAYINT_FUZZ_TARGET=pfm_reader scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted image outside 1..kMaxImageSide on a side, or whose pixel count is not
//     width x height.
// Each check traps, so the input is saved as a crash artifact.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"
#include "rayint/render/float_image.hpp"

namespace {

constexpr const char* kSource = "fuzz.pfm";

void require(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const rayint::Image image = rayint::decode_pfm(bytes, kSource);
    require(image.width >= 1 && image.height >= 1 && image.width <= rayint::kMaxImageSide &&
            image.height <= rayint::kMaxImageSide);
    require(image.pixels.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  } catch (const rayint::InputError& e) {
    const std::string what = e.what();
    const std::string prefix = std::string(kSource) + ": ";
    require(what.compare(0, prefix.size(), prefix) == 0);
    require(what.find('\n') == std::string::npos && what.find('\r') == std::string::npos);
  }
  return 0;
}
