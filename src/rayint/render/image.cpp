#include "rayint/render/image.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "rayint/core/atomic_file.hpp"
#include "rayint/core/default_init.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/limits.hpp"
#include "rayint/core/prefaulted.hpp"

namespace rayint {

Image::Image(int w, int h, Rgb fill) : width(w), height(h) {
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  // The pages in one call before the fill writes them all, the whole 2 MiB pages inside the block
  // in huge pages (core/prefaulted.hpp: a 512 x 512 image's ~1,500 page faults were ~2% of a
  // 105k-tet render's CPU; populated 4 KiB pages still cost ~8 us at the first write on the Zen 5
  // VM: the fill's perf samples 170 -> 57 in one 105k render each, same PNG; issue 33).
  pixels.reserve(n);
  prefault_capacity(pixels);
  pixels.assign(n, fill);
}

Rgb Image::sample(double u, double v) const {
  if (width == 0 || height == 0) return Rgb{0.0, 0.0, 0.0};
  const double fx = std::clamp(u * width - 0.5, 0.0, width - 1.0);
  const double fy = std::clamp(v * height - 0.5, 0.0, height - 1.0);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const double ax = fx - x0, ay = fy - y0;
  Rgb out{};
  for (int c = 0; c < 3; ++c) {
    const double top = (1 - ax) * at(x0, y0)[c] + ax * at(x1, y0)[c];
    const double bottom = (1 - ax) * at(x0, y1)[c] + ax * at(x1, y1)[c];
    out[c] = (1 - ay) * top + ay * bottom;
  }
  return out;
}

double srgb_encode(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

namespace {

// The 8-bit code as the PNG writer formed it per sample before (a std::pow per channel: ~1.7%
// of a 512 x 512 render's CPU at 105k tets, issue 33); v in [0, 1].
int srgb_code_by_pow(double v) { return static_cast<int>(std::lround(srgb_encode(v) * 255.0)); }

// The code as a table lookup. bound[q] is the smallest double v with code(v) > q: from
// srgb_decode's estimate of where 255 srgb_encode(v) crosses q + 1/2, stepped ulp by ulp against
// srgb_code_by_pow itself; a value's code is the number of bounds <= it. That is exact where the
// pow formula is monotone, and its rounding (a few ulps of 255 srgb_encode, whose slope is >= 112
// on [0, 1]) can break that only within ~1e-14 of a bound: values within kNear of one take the
// pow formula. The lookup: [0, 1] in 4096 buckets, each holding at most one bound (the code's
// slope is <= 255 * 12.92 = 3,295 per unit < 4096; checked as the table is built), so a value's
// code is its bucket's first code plus one compare. Tests ([image]): every bound +-200 ulps and
// 10^6 random values against srgb_code_by_pow.
class Srgb8Table {
 public:
  Srgb8Table() {
    for (int q = 0; q < 255; ++q) {
      double v = srgb_decode((q + 0.5) / 255.0);
      while (srgb_code_by_pow(v) <= q) v = std::nextafter(v, 2.0);
      while (v > 0.0 && srgb_code_by_pow(std::nextafter(v, -1.0)) > q) v = std::nextafter(v, -1.0);
      bound_[static_cast<std::size_t>(q)] = v;
    }
    std::size_t q = 0;
    for (std::size_t b = 0; b <= kBuckets; ++b) {
      const double lo = static_cast<double>(b) / kBuckets;
      while (q < 255 && bound_[q] <= lo) ++q;
      first_[b] = static_cast<std::uint8_t>(q);
      const double hi = static_cast<double>(b + 1) / kBuckets;
      if (q + 1 < 255 && bound_[q + 1] < hi) throw std::logic_error("srgb_encode_8bit: two code bounds in one bucket");
    }
  }
  std::uint8_t code(double v) const {
    if (!(v > 0.0)) return 0;  // NaN, negative or zero
    if (v >= 1.0) return 255;
    const std::size_t q = first_[static_cast<std::size_t>(v * kBuckets)];  // v * 4096 is exact
    const std::size_t c = q < 255 && v >= bound_[q] ? q + 1 : q;
    if ((c < 255 && bound_[c] - v <= kNear) || (c > 0 && v - bound_[c - 1] <= kNear))
      return static_cast<std::uint8_t>(srgb_code_by_pow(v));
    return static_cast<std::uint8_t>(c);
  }

 private:
  static constexpr std::size_t kBuckets = 4096;
  static constexpr double kNear = 1e-12;
  std::array<double, 255> bound_{};
  std::array<std::uint8_t, kBuckets + 1> first_{};
};

}  // namespace

std::uint8_t srgb_encode_8bit(double linear) {
  static const Srgb8Table table;  // ~1,000 pow calls, once
  return table.code(linear);
}

std::string encode_png(const Image& image, const PngOptions& options) {
  if (image.width < 1 || image.height < 1) throw std::runtime_error("encode_png: empty image");
  std::vector<std::uint8_t, DefaultInitAllocator<std::uint8_t>> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  populate_pages(rgb.data(), rgb.size());  // written in full below: its pages in one call
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      double v = image.pixels[i][c] * options.exposure;
      if (!std::isfinite(v)) v = 0.0;  // a NaN pixel shows black rather than poisoning the file
      rgb[3 * i + c] = options.srgb ? srgb_encode_8bit(v)
                                    : static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    }
  }
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  // libpng's speed setting (no row filters, zlib level 3): the PNG is a preview, and its deflate
  // at the default setting was ~6% of a 512 x 512 render's CPU at 105k tets (issue 33). The same
  // pixels; the file is larger or smaller by the image (render-13-vtk at 512 x 512: 76,004 ->
  // 96,101 bytes, 28.6 -> 3.9 ms; reports/scaling/NOTES.md, round 12).
  png.flags = PNG_IMAGE_FLAG_FAST;
  // One pass into a buffer of the format's bound: with a null buffer libpng compresses the whole
  // image once only to report its size, and then again. The buffer is left uninitialised (its
  // untouched pages never become resident: the bound is ~ the raw RGB size, 805 MB at 16384^2)
  // and the file is copied out at its own size.
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  const std::unique_ptr<char[]> buffer(new char[size]);
  if (!png_image_write_to_memory(&png, buffer.get(), &size, 0, rgb.data(), 0, nullptr))
    throw std::runtime_error(std::string("PNG encoding failed: ") + png.message);
  return std::string(buffer.get(), size);
}

void write_png(const std::string& path, const Image& image, const PngOptions& options) {
  write_file_atomically(path, encode_png(image, options));
}

ImageSize read_png_size(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))  // the signature and IHDR only
    throw InputError(path + ": cannot read PNG (" + png.message + ")");
  const ImageSize size{static_cast<int>(std::min<png_uint_32>(png.width, 1u << 30)),
                       static_cast<int>(std::min<png_uint_32>(png.height, 1u << 30))};
  png_image_free(&png);
  return size;
}

Image read_png(const std::string& path, bool srgb) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw InputError(path + ": cannot read PNG (" + png.message + ")");
  png.format = PNG_FORMAT_RGB;
  if (png.width > 16384 || png.height > 16384) {
    png_image_free(&png);
    throw InputError(path + ": PNG larger than 16384 x 16384");
  }
  try {  // a decompression bomb (a small file of a huge image) is refused before decoding
    limits::check(limits::kImageBytes, static_cast<double>(png.width) * png.height * (3.0 + sizeof(Rgb)),
                  path + ": (image): " + std::to_string(png.width) + " x " + std::to_string(png.height) + " pixels");
  } catch (...) {
    png_image_free(&png);
    throw;
  }
  std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, rgb.data(), 0, nullptr))
    throw InputError(path + ": cannot decode PNG (" + png.message + ")");
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = rgb[3 * i + c] / 255.0;
      image.pixels[i][c] = srgb ? srgb_decode(v) : v;
    }
  return image;
}

}  // namespace rayint
