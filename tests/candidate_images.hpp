#pragma once
// Candidate images for the z-test of `rayint check --candidate-image ... --candidate-variance`
// (tests of camera cases and of scenes): a "Monte Carlo" candidate off by a set amount from a
// reference image, one biased far beyond its noise, and the constant variance image both carry.
#include <filesystem>

#include "rayint/render/float_image.hpp"

namespace rayint::test {

// Writes into `dir`: mc.npy, `ref` + `offset` in every channel of every pixel; biased.npy,
// `ref` + `bias`; var.npy, `variance` in every channel (per sample or of the mean, as the
// test's --samples says).
inline void write_z_test_candidates(const std::filesystem::path& dir, const Image& ref, double variance,
                                    double offset, double bias) {
  Image off = ref, biased = ref, var(ref.width, ref.height, Rgb{variance, variance, variance});
  for (auto& p : off.pixels) for (double& v : p) v += offset;
  for (auto& p : biased.pixels) for (double& v : p) v += bias;
  write_image((dir / "mc.npy").string(), off);
  write_image((dir / "biased.npy").string(), biased);
  write_image((dir / "var.npy").string(), var);
}

}  // namespace rayint::test
