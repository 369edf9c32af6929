// libFuzzer target for the NumPy .npy reader of `rayint check --candidate-image`
// (rayint::decode_npy, render/float_image.hpp) on arbitrary bytes. Run it with
// `RAYINT_FUZZ_TARGET=npy_reader scripts/fuzz.sh`. A finding is any of:
//   - a crash, sanitizer report, hang or leak;
//   - an exception other than rayint::InputError escaping (reported as a deadly signal);
//   - an InputError whose message is not one line starting with "<source>: ";
//   - an accepted image outside 1..kMaxImageSide on a side, or whose pixel count is not
//     width x height (fuzz/image_fuzz_checks.hpp).
// Each check traps, so the input is saved as a crash artifact.
#include <cstddef>
#include <cstdint>

#include "image_fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rayint::fuzz::check_image_decoder(&rayint::decode_npy, data, size, "fuzz.npy");
}
