#pragma once
// A renderer's image (the "candidate") against the exact image of the same camera, pixel by pixel
// (`rayint check CASE --candidate-image IMAGE`, README "Checking a renderer's image").
//
// Pixel convention: render/float_image.hpp (pixel centres, row 0 at the top, y down). A renderer
// whose rows run bottom-up (OpenGL read-back) or whose x runs right-to-left passes --flip-y /
// --flip-x, which mirror the candidate before it is compared.
//
// Pass rule, per pixel and channel, the same as the per-ray check (studies/check.hpp):
//   |got - expected| <= max(abs_tol, rel_tol * |expected|);  a non-finite `got` fails.
// The image passes when every channel of every pixel passes.
//
// Figures (core/statistics.hpp's p99 is the nearest rank, so it is a real pixel):
//   abs error   |got - expected| per channel; max, mean, p99 over all channels of all pixels
//   rel error   per pixel, the largest over channels of |got - expected| / |expected|
//               (0 when both are 0, +inf when expected is 0 and got is not); max, mean, p99
//   PSNR        10 log10(peak^2 / MSE), peak = largest |expected| over the image, MSE over all
//               channels; +inf when the images are equal
//   worst       the pixels with the largest ratio abs error / allowed, most exceeding first.
#include <cstddef>
#include <vector>

#include "rayint/render/image.hpp"

namespace rayint {

struct ImageCompareOptions {
  double rel_tol = 1e-6;
  double abs_tol = 0.0;
  int worst = 3;  // how many worst pixels to list
};

struct PixelDiff {
  int x = 0, y = 0;
  int channel = 0;          // the channel with the largest ratio
  double expected = 0.0, got = 0.0;
  double abs_error = 0.0, rel_error = 0.0;
  double allowed = 0.0;     // max(abs_tol, rel_tol * |expected|)
  double ratio = 0.0;       // abs_error / allowed (+inf when allowed is 0 and the error is not)
  bool pass = false;
};

struct ImageComparison {
  int width = 0, height = 0;
  long pixels = 0, failed_pixels = 0, failed_channels = 0, non_finite = 0;
  double max_abs = 0.0, mean_abs = 0.0, p99_abs = 0.0;
  double max_rel = 0.0, mean_rel = 0.0, p99_rel = 0.0;  // mean over finite values
  double psnr = 0.0;
  double fraction_within = 0.0;      // pixels whose three channels pass / pixels
  std::vector<double> rel_error;     // per pixel, row-major (for the heat map)
  std::vector<PixelDiff> worst;      // sorted, most exceeding first
  bool pass = false;
};

// Monte Carlo candidates: a per-pixel z-test against the exact image (the pattern of Mitsuba 3's
// render tests, src/render/tests/test_render.py: z = |mean - reference| / sigma, two-sided
// p = erfc(|z| / sqrt 2), a multiple-comparison correction, pass when the fraction of passing
// tests reaches a threshold). Here:
//   - one test per pixel and channel, sigma^2 = the candidate's variance OF THE MEAN at that
//     pixel (the caller divides a per-sample variance by the sample count); the reference is
//     exact, so it adds no variance (Mitsuba's reference is itself Monte Carlo);
//   - the correction is HOLM-BONFERRONI at family level alpha: sort the m p-values, reject
//     p_(k) while p_(k) <= alpha / (m - k + 1). It bounds the probability of rejecting ANY
//     pixel of a correct renderer by alpha under any dependence between pixels (a renderer's
//     pixels share random streams and scene paths, so independence, which Mitsuba's Sidak
//     correction assumes, is not given), and rejects at least as many as plain Bonferroni.
//     Benjamini-Hochberg controls the expected fraction of false rejections instead, which does
//     not bound how often a correct renderer's CI goes red, so it is not used.
//   - pass when (tests not rejected) / m >= min_fraction. With min_fraction = 1 the false-failure
//     rate is <= alpha (1 %); the default 0.9975 (Mitsuba's) tolerates a few rejections from
//     pixels where the normal approximation fails (few samples, a zero sample variance).
//   A pixel with sigma = 0 passes only when mean == reference (z = 0/0 is taken as 0).
// The measured false-failure rate on rayint's own path tracer is in the README.
struct ZTestOptions {
  double alpha = 0.01;
  double min_fraction = 0.9975;
};

struct ZTestResult {
  long tests = 0, rejected = 0;
  double fraction_passing = 0.0;
  double min_p = 1.0;         // smallest p-value
  double holm_threshold = 0;  // alpha / m: the threshold the smallest p-value is held to
  int worst_x = 0, worst_y = 0, worst_channel = 0;
  double worst_z = 0.0;       // |z| at the smallest p-value
  std::vector<bool> pixel_rejected;  // per pixel (any channel), row-major
  bool pass = false;
};

// Throws std::invalid_argument on different sizes or a negative / non-finite variance.
ZTestResult z_test_images(const Image& exact, const Image& mean, const Image& variance_of_mean,
                          const ZTestOptions& options);

// Mirrors an image left-right and/or top-bottom.
Image flipped(const Image& image, bool flip_x, bool flip_y);

// How a candidate's alpha channel is meant: `ignore` (only RGB is compared, the renderer already
// composited over the background), `premultiplied` (RGB = emitted colour C, alpha = 1 - T: the
// pixel is C + (1 - alpha) * background, Porter-Duff "over" with associated alpha, which is what
// VTK's ray caster stores and what glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA) leaves in a frame
// buffer cleared to transparent black), `straight` (RGB = C / alpha: alpha * RGB + (1 - alpha) *
// background).
enum class AlphaMode { ignore, premultiplied, straight };

// The candidate composited over a uniform background. Throws std::invalid_argument when `alpha`
// does not have one value per pixel, or names the first pixel "(x, y)" whose alpha is not a
// finite number in [0, 1].
Image composite_over(const Image& rgb, const std::vector<double>& alpha, const Rgb& background, AlphaMode mode);

// Throws std::invalid_argument when the sizes differ (the CLI reports it as bad input).
ImageComparison compare_images(const Image& expected, const Image& candidate,
                               const ImageCompareOptions& options);

}  // namespace rayint
