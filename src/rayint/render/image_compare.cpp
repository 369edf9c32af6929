// Pixel-by-pixel comparison of a candidate image with the exact one (see image_compare.hpp).
#include "rayint/render/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "rayint/core/statistics.hpp"

namespace rayint {

Image flipped(const Image& image, bool flip_x, bool flip_y) {
  Image out(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      out.at(x, y) = image.at(flip_x ? image.width - 1 - x : x, flip_y ? image.height - 1 - y : y);
  return out;
}

Image composite_over(const Image& rgb, const std::vector<double>& alpha, const Rgb& background,
                     AlphaMode mode) {
  if (mode == AlphaMode::ignore) return rgb;
  if (alpha.size() != rgb.pixels.size())
    throw std::invalid_argument("the image has no alpha channel (an .npy of shape (height, width, 4) "
                                "or an .exr with channel A is needed)");
  Image out(rgb.width, rgb.height);
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    const double a = alpha[i];
    if (!(a >= 0.0 && a <= 1.0))
      throw std::invalid_argument(
          "pixel(" + std::to_string(i % static_cast<std::size_t>(rgb.width)) + "," +
          std::to_string(i / static_cast<std::size_t>(rgb.width)) + "): alpha must be in [0, 1], got " +
          std::to_string(a));
    for (int c = 0; c < 3; ++c) {
      const double emitted = mode == AlphaMode::premultiplied ? rgb.pixels[i][c] : a * rgb.pixels[i][c];
      out.pixels[i][c] = emitted + (1.0 - a) * background[c];
    }
  }
  return out;
}

ImageComparison compare_images(const Image& expected, const Image& candidate,
                               const ImageCompareOptions& o) {
  if (expected.width != candidate.width || expected.height != candidate.height)
    throw std::invalid_argument("candidate image is " + std::to_string(candidate.width) + " x " +
                                std::to_string(candidate.height) + ", the camera's is " +
                                std::to_string(expected.width) + " x " +
                                std::to_string(expected.height));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  ImageComparison r;
  r.width = expected.width;
  r.height = expected.height;
  r.pixels = static_cast<long>(expected.pixels.size());
  r.rel_error.assign(expected.pixels.size(), 0.0);
  std::vector<double> abs_all;
  abs_all.reserve(expected.pixels.size() * 3);
  std::vector<PixelDiff> per_pixel(expected.pixels.size());
  double peak = 0.0, sq_sum = 0.0, abs_sum = 0.0, rel_sum = 0.0;
  long finite_abs = 0, finite_rel = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) {
    PixelDiff worst;
    worst.x = static_cast<int>(i % static_cast<std::size_t>(r.width));
    worst.y = static_cast<int>(i / static_cast<std::size_t>(r.width));
    worst.ratio = -1.0;
    bool pixel_pass = true;
    double pixel_rel = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double e = expected.pixels[i][c], g = candidate.pixels[i][c];
      peak = std::max(peak, std::fabs(e));
      const bool finite = std::isfinite(g);
      const double abs_error = finite ? std::fabs(g - e) : kInf;
      const double rel_error = !finite ? kInf
                               : e == 0.0 ? (g == 0.0 ? 0.0 : kInf)
                                          : abs_error / std::fabs(e);
      const double allowed = std::max(o.abs_tol, o.rel_tol * std::fabs(e));
      const bool pass = finite && abs_error <= allowed;
      const double ratio = allowed > 0.0 ? abs_error / allowed : (abs_error > 0.0 ? kInf : 0.0);
      if (!finite) ++r.non_finite;
      if (!pass) ++r.failed_channels;
      pixel_pass = pixel_pass && pass;
      pixel_rel = std::max(pixel_rel, rel_error);
      abs_all.push_back(abs_error);
      if (std::isfinite(abs_error)) {
        abs_sum += abs_error;
        sq_sum += abs_error * abs_error;
        ++finite_abs;
      } else {
        sq_sum = kInf;
      }
      if (ratio > worst.ratio || (!pass && worst.pass)) {
        worst.channel = c;
        worst.expected = e;
        worst.got = g;
        worst.abs_error = abs_error;
        worst.rel_error = rel_error;
        worst.allowed = allowed;
        worst.ratio = ratio;
      }
      worst.pass = pixel_pass;
    }
    worst.pass = pixel_pass;
    per_pixel[i] = worst;
    r.rel_error[i] = pixel_rel;
    if (std::isfinite(pixel_rel)) {
      rel_sum += pixel_rel;
      ++finite_rel;
    }
    if (!pixel_pass) ++r.failed_pixels;
  }
  const ErrorStats abs_stats = error_stats(abs_all);
  r.max_abs = abs_stats.max;
  r.p99_abs = abs_stats.p99;
  r.mean_abs = finite_abs > 0 ? abs_sum / static_cast<double>(finite_abs) : 0.0;
  const ErrorStats rel_stats = error_stats(r.rel_error);
  r.max_rel = rel_stats.max;
  r.p99_rel = rel_stats.p99;
  r.mean_rel = finite_rel > 0 ? rel_sum / static_cast<double>(finite_rel) : 0.0;
  const double mse = sq_sum / static_cast<double>(abs_all.size());
  r.psnr = mse == 0.0 ? kInf : (std::isfinite(mse) && peak > 0.0 ? 10.0 * std::log10(peak * peak / mse) : -kInf);
  r.fraction_within = r.pixels > 0 ? static_cast<double>(r.pixels - r.failed_pixels) / static_cast<double>(r.pixels) : 1.0;
  r.pass = r.failed_pixels == 0;
  // The worst pixels: largest ratio first, ties by row-major index (a stable, reproducible order).
  std::vector<std::size_t> order(per_pixel.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(std::max(o.worst, 0)), order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order.end(),
                    [&](std::size_t a, std::size_t b) {
                      if (per_pixel[a].ratio != per_pixel[b].ratio) return per_pixel[a].ratio > per_pixel[b].ratio;
                      return a < b;
                    });
  for (std::size_t j = 0; j < k; ++j) r.worst.push_back(per_pixel[order[j]]);
  return r;
}

ZTestResult z_test_images(const Image& exact, const Image& mean, const Image& var,
                          const ZTestOptions& o) {
  if (exact.width != mean.width || exact.height != mean.height || var.width != mean.width ||
      var.height != mean.height)
    throw std::invalid_argument("the mean, variance and exact images differ in size");
  const std::size_t n = exact.pixels.size();
  ZTestResult r;
  r.tests = static_cast<long>(3 * n);
  std::vector<double> p(3 * n), z(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = var.pixels[i][c];
      if (!(v >= 0.0) || !std::isfinite(v))
        throw std::invalid_argument("variance at pixel (" + std::to_string(i % static_cast<std::size_t>(exact.width)) +
                                    ", " + std::to_string(i / static_cast<std::size_t>(exact.width)) +
                                    ") is negative or not finite");
      const double d = std::fabs(mean.pixels[i][c] - exact.pixels[i][c]);
      double zz;
      if (!std::isfinite(mean.pixels[i][c])) zz = std::numeric_limits<double>::infinity();
      else if (d == 0.0) zz = 0.0;
      else zz = d / std::sqrt(v);  // +inf when v == 0
      z[3 * i + c] = zz;
      p[3 * i + c] = std::erfc(zz / std::sqrt(2.0));
    }
  // Holm's step-down procedure.
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  const double m = static_cast<double>(p.size());
  r.pixel_rejected.assign(n, false);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (p[order[k]] > o.alpha / (m - static_cast<double>(k))) break;
    ++r.rejected;
    r.pixel_rejected[order[k] / 3] = true;
  }
  if (!order.empty()) {
    const std::size_t w = order.front();
    r.min_p = p[w];
    r.worst_z = z[w];
    r.worst_x = static_cast<int>((w / 3) % static_cast<std::size_t>(exact.width));
    r.worst_y = static_cast<int>((w / 3) / static_cast<std::size_t>(exact.width));
    r.worst_channel = static_cast<int>(w % 3);
  }
  r.holm_threshold = o.alpha / m;
  r.fraction_passing = r.tests > 0 ? static_cast<double>(r.tests - r.rejected) / m : 1.0;
  r.pass = r.fraction_passing >= o.min_fraction;
  return r;
}

}  // namespace rayint
