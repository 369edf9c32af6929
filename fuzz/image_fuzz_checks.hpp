#pragma once
// What the float-image fuzz targets (exr_reader, npy_reader, pfm_reader) check: a decoder of
// `rayint check --candidate-image` on arbitrary bytes refuses with one InputError line starting
// "<source>: ", and an image it accepts has 1..kMaxImageSide pixels a side and width x height
// pixels. Each check traps, so the input is saved as a crash artifact.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "rayint/render/float_image.hpp"
#include "fuzz_checks.hpp"

namespace rayint::fuzz {

inline int check_image_decoder(Image (*decode)(std::string_view, const std::string&), const std::uint8_t* data,
                               std::size_t size, const std::string& source) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  return refusals_are_one_line(source, [&] {
    const Image image = decode(bytes, source);
    require(image.width >= 1 && image.height >= 1 && image.width <= kMaxImageSide && image.height <= kMaxImageSide);
    require(image.pixels.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  });
}

}  // namespace rayint::fuzz
