#pragma once
// An RGB image of linear radiance values, and its PNG form (libpng's simplified API).
// PNG files are 8-bit sRGB: writing scales by `exposure`, clamps to [0, 1] and applies the sRGB
// transfer curve; reading inverts the curve, so a background image read from PNG is linear.
// They are previews, written with libpng's speed setting (PNG_IMAGE_FLAG_FAST: no row filters,
// zlib level 3); the float formats (render/float_image.hpp) are the exact ones.
#include <cstdint>
#include <string>
#include <vector>

#include "rayint/model/transfer_function.hpp"  // Rgb

namespace rayint {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  // row-major, row 0 at the top

  Image() = default;
  Image(int w, int h, Rgb fill = Rgb{0.0, 0.0, 0.0});
  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
  // Bilinear lookup at normalized coordinates (u, v) in [0, 1]^2, v = 0 at the top; clamped.
  Rgb sample(double u, double v) const;
};

struct PngOptions {
  double exposure = 1.0;  // radiance multiplier before clamping
  bool srgb = true;       // apply the sRGB transfer curve (false: store linear values)
};

// Encodes to PNG bytes; throws std::runtime_error on a libpng failure.
std::string encode_png(const Image& image, const PngOptions& options = {});
// Encodes and writes atomically (no partial file on failure).
void write_png(const std::string& path, const Image& image, const PngOptions& options = {});
// Reads any PNG libpng reads (grey, palette, alpha are converted to RGB); linear values in
// [0, 1]. Throws InputError "<path>: ..." on an unreadable or malformed file.
Image read_png(const std::string& path, bool srgb = true);
// A PNG's width and height from its header (IHDR), without decoding it.
struct ImageSize {
  int width = 0, height = 0;
};
ImageSize read_png_size(const std::string& path);

double srgb_encode(double linear);  // [0,1] -> [0,1]
double srgb_decode(double encoded); // [0,1] -> [0,1]
// The PNG's 8-bit sRGB code of a linear value: exactly lround(255 * srgb_encode(v)) for every
// double v (NaN: 0), without a pow per sample (a table of the 255 code boundaries).
std::uint8_t srgb_encode_8bit(double linear);

}  // namespace rayint
