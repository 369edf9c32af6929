#pragma once
// Max's procedural cloud (1995, Sec. 2, the figures): "a sum of ellipsoidal densities", with
// "a noise texture [Perlin 1985] to give a natural fractal appearance at the edges".
//
//   base(p)    = sum_k w_k * (1 - r_k(p)^2)^2 for r_k < 1, else 0, r_k = |(p - c_k) / radii_k|
//   fbm(p)     = sum_{o < octaves} gain^o * perlin(frequency * lacunarity^o * p + offset)
//   density(p) = scale * max(0, base(p) + amplitude * fbm(p) - threshold)   inside bounds
//
// perlin() is Perlin's improved gradient noise (2002: quintic fade, 12 gradient directions) on a
// permutation table shuffled by std::mt19937_64(seed), so a cloud is reproducible from its seed
// on every platform (the shuffle is written out, not std::shuffle). We take |perlin| < 1.1
// (improved noise stays near [-1, 1]; tests/test_scene_pipeline.cpp samples 600,000 points and
// checks the bound), so max_density() = scale * (sum w_k + amplitude * 1.1 * sum gain^o -
// threshold) is an upper bound of the density.
// bounds() is the union of the ellipsoids' boxes; density is 0 outside it (with threshold >=
// amplitude * 1.1 * sum gain^o the field is also 0 outside the ellipsoids, so nothing is cut).
// The field is continuous, with a kink on the iso-surface base + amplitude * fbm = threshold.
#include <array>
#include <cstdint>
#include <vector>

#include "rayint/media/medium.hpp"

namespace rayint {

class PerlinNoise {
 public:
  explicit PerlinNoise(std::uint64_t seed);
  double operator()(const Vec3& p) const;  // in about [-1, 1]

 private:
  std::array<int, 512> perm_{};
};

struct Ellipsoid {
  Vec3 center = Vec3::Zero();
  Vec3 radii = Vec3::Ones();
  double weight = 1.0;
};

struct CloudParams {
  std::vector<Ellipsoid> ellipsoids;
  double scale = 1.0;
  double threshold = 0.0;
  double amplitude = 0.0;
  double frequency = 1.0;
  int octaves = 4;
  double lacunarity = 2.0;
  double gain = 0.5;
  std::uint64_t seed = 1;
};

class CloudField final : public DensityField {
 public:
  explicit CloudField(CloudParams params);
  std::string kind() const override { return "cloud"; }
  Bounds bounds() const override { return bounds_; }
  double density(const Vec3& p) const override;
  double max_density() const override { return max_density_; }
  double gradient_step() const override { return gradient_step_; }
  // The finest noise wavelength (or the smallest ellipsoid radius, if smaller).
  double feature_length() const override { return feature_length_; }
  const CloudParams& params() const { return params_; }

 private:
  double base(const Vec3& p) const;
  double fbm(const Vec3& p) const;
  CloudParams params_;
  PerlinNoise noise_;
  Bounds bounds_;
  double max_density_ = 0.0;
  double gradient_step_ = 1e-3;
  double feature_length_ = 1.0;
};

// The cloud of the bundled figure scenes (cases/scenes/): five ellipsoids around the origin,
// about 2.4 x 1.2 x 1.4 in size, with 5 octaves of noise.
CloudParams max_figure_cloud(std::uint64_t seed = 7);

}  // namespace rayint
