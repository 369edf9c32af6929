#pragma once
// Float images: the exact values of a render, written and read without the 8-bit rounding of
// PNG, so a renderer's CI can compare what it actually writes (`rayint check --candidate-image`).
//
// Pixel convention of rayint (geometry/camera.hpp, the same in every format below): pixel (x, y)
// is the ray through the pixel CENTRE ((x + 0.5)/width, (y + 0.5)/height) of the image plane;
// row y = 0 is the TOP of the image and y runs DOWN; x = 0 is the left. Each format stores that
// image in its own row order, and the readers undo it, so a file written here reads back equal:
//
//   .pfm  Portable Float Map ("PF" RGB, "Pf" grey), float32. The format stores rows BOTTOM TO
//         TOP; written little-endian (scale -1). Reading accepts either byte order and any scale
//         (the values are not multiplied by it: the scale only carries the byte order).
//   .exr  OpenEXR (Debian libopenexr-dev, the library's own Imf::OutputFile / Imf::InputFile with
//         a FrameBuffer of 32-bit FLOAT slices), channels R, G, B, ZIP compression, rows top to
//         bottom in the data window. Reading accepts HALF, FLOAT or UINT channels (converted by
//         OpenEXR), a Y channel alone as grey, and any data window (its top-left is pixel 0, 0).
//   .npy  NumPy array, FLOAT64 ('<f8'), shape (height, width, 3), C order: a[y, x, c] with y = 0
//         the top row, as matplotlib's imshow shows it. Reading accepts '<f8', '<f4', '>f8',
//         '>f4', shapes (H, W), (H, W, 1), (H, W, 3), (H, W, 4) (alpha dropped by read_image,
//         kept by read_image_with_alpha), C order only.
//   .png  the 8-bit sRGB preview (render/image.hpp); read back linear, so only to ~1/255.
//
// Every reader throws InputError "<file>: <what>" (one line) on a malformed or unsupported file
// and refuses images wider or taller than kMaxImageSide; none crashes on arbitrary bytes (a
// libFuzzer target each, fuzz/).
#include <string>
#include <string_view>
#include <vector>

#include "rayint/render/image.hpp"

namespace rayint {

enum class ImageFormat { png, pfm, exr, npy };

inline constexpr int kMaxImageSide = 16384;

// The format named by a file's extension (case-insensitive); throws InputError
// "<path>: unknown image extension ..." for anything else.
ImageFormat image_format_of(const std::string& path);

std::string encode_pfm(const Image& image);
std::string encode_exr(const Image& image);
std::string encode_npy(const Image& image);

// Parse bytes already in memory; `source` names them in messages.
Image decode_pfm(std::string_view bytes, const std::string& source);
Image decode_exr(std::string_view bytes, const std::string& source);
Image decode_npy(std::string_view bytes, const std::string& source);

// Writes by extension, atomically (core/atomic_file.hpp); png uses `png_options`.
void write_image(const std::string& path, const Image& image, const PngOptions& png_options = {});
// Reads by extension (png: sRGB-decoded to linear). Throws InputError.
Image read_image(const std::string& path);

// The width and height a file declares, from its header alone (PNG's IHDR, the .npy and .pfm
// headers, the .exr data window): a candidate of the wrong size, or one too large to hold, is
// refused before its pixels are read or decoded. Throws InputError as the readers do.
ImageSize read_image_size(const std::string& path);

// An image with the alpha channel its file carries: .npy of shape (H, W, 4) (the 4th channel) or
// .exr with an "A" channel; `alpha` is empty for every other file (PFM and RGB files have none,
// PNG's alpha is folded into RGB by read_png). `rgb` is what read_image returns.
struct ImageWithAlpha {
  Image rgb;
  std::vector<double> alpha;  // row-major like rgb.pixels, or empty
};
ImageWithAlpha read_image_with_alpha(const std::string& path);
ImageWithAlpha decode_npy_with_alpha(std::string_view bytes, const std::string& source);
ImageWithAlpha decode_exr_with_alpha(std::string_view bytes, const std::string& source);

}  // namespace rayint
