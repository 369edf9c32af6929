#include "rayint/scene/cloud.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace rayint {
namespace {

double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
double lerp(double t, double a, double b) { return a + t * (b - a); }
double grad(int hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y;
  const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

constexpr double kNoiseBound = 1.1;  // |perlin| over all of space stays below this

}  // namespace

PerlinNoise::PerlinNoise(std::uint64_t seed) {
  std::array<int, 256> p{};
  for (int i = 0; i < 256; ++i) p[static_cast<std::size_t>(i)] = i;
  std::mt19937_64 rng(seed);
  for (int i = 255; i > 0; --i) {  // Fisher-Yates, written out so every library gives the same
    const auto j = static_cast<int>(rng() % static_cast<std::uint64_t>(i + 1));
    std::swap(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)]);
  }
  for (std::size_t i = 0; i < 512; ++i) perm_[i] = p[i & 255];
}

double PerlinNoise::operator()(const Vec3& q) const {
  const double fx = std::floor(q.x()), fy = std::floor(q.y()), fz = std::floor(q.z());
  const int X = static_cast<int>(static_cast<long long>(fx) & 255);
  const int Y = static_cast<int>(static_cast<long long>(fy) & 255);
  const int Z = static_cast<int>(static_cast<long long>(fz) & 255);
  const double x = q.x() - fx, y = q.y() - fy, z = q.z() - fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  auto P = [this](int i) { return perm_[static_cast<std::size_t>(i)]; };
  const int A = P(X) + Y, AA = P(A) + Z, AB = P(A + 1) + Z;
  const int B = P(X + 1) + Y, BA = P(B) + Z, BB = P(B + 1) + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(P(AA), x, y, z), grad(P(BA), x - 1, y, z)),
                   lerp(u, grad(P(AB), x, y - 1, z), grad(P(BB), x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(P(AA + 1), x, y, z - 1), grad(P(BA + 1), x - 1, y, z - 1)),
                   lerp(u, grad(P(AB + 1), x, y - 1, z - 1), grad(P(BB + 1), x - 1, y - 1, z - 1))));
}

CloudField::CloudField(CloudParams params) : params_(std::move(params)), noise_(params_.seed) {
  if (params_.ellipsoids.empty()) throw std::invalid_argument("a cloud needs at least one ellipsoid");
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  double wsum = 0.0;
  double rmin = std::numeric_limits<double>::infinity();
  for (const Ellipsoid& e : params_.ellipsoids) {
    lo = lo.cwiseMin(e.center - e.radii);
    hi = hi.cwiseMax(e.center + e.radii);
    wsum += e.weight;
    rmin = std::min(rmin, e.radii.minCoeff());
  }
  bounds_ = {lo, hi};
  double gsum = 0.0;
  for (int o = 0; o < params_.octaves; ++o) gsum += std::pow(params_.gain, o);
  max_density_ = params_.scale * std::max(0.0, wsum + params_.amplitude * kNoiseBound * gsum - params_.threshold);
  // Central differences at 1/20 of the finest noise wavelength (and of the smallest radius).
  const double finest = 1.0 / (params_.frequency * std::pow(params_.lacunarity, std::max(0, params_.octaves - 1)));
  feature_length_ = std::min(finest, rmin);
  gradient_step_ = 0.05 * feature_length_;
}

double CloudField::base(const Vec3& p) const {
  double b = 0.0;
  for (const Ellipsoid& e : params_.ellipsoids) {
    const double r2 = (p - e.center).cwiseQuotient(e.radii).squaredNorm();
    if (r2 < 1.0) b += e.weight * (1.0 - r2) * (1.0 - r2);
  }
  return b;
}

double CloudField::fbm(const Vec3& p) const {
  double sum = 0.0, amp = 1.0, f = params_.frequency;
  for (int o = 0; o < params_.octaves; ++o) {
    // Each octave is offset so the lattice origins of the octaves do not line up.
    sum += amp * noise_(p * f + Vec3(17.31 * o, 5.77 * o, 11.13 * o));
    amp *= params_.gain;
    f *= params_.lacunarity;
  }
  return sum;
}

double CloudField::density(const Vec3& p) const {
  if (!bounds_.contains(p)) return 0.0;
  const double x = base(p) + (params_.amplitude != 0.0 ? params_.amplitude * fbm(p) : 0.0) - params_.threshold;
  return x > 0.0 ? params_.scale * x : 0.0;
}

CloudParams max_figure_cloud(std::uint64_t seed) {
  CloudParams c;
  c.ellipsoids = {
      {Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.55, 0.6), 1.0},
      {Vec3(-0.6, 0.15, 0.1), Vec3(0.55, 0.5, 0.5), 0.9},
      {Vec3(0.55, 0.2, -0.1), Vec3(0.6, 0.55, 0.5), 0.9},
      {Vec3(0.1, 0.4, 0.0), Vec3(0.5, 0.45, 0.45), 0.8},
      {Vec3(-0.2, -0.2, 0.3), Vec3(0.7, 0.35, 0.45), 0.6},
  };
  c.scale = 1.0;
  c.threshold = 0.55;
  c.amplitude = 0.6;
  c.frequency = 3.0;
  c.octaves = 5;
  c.lacunarity = 2.0;
  c.gain = 0.5;
  c.seed = seed;
  return c;
}

}  // namespace rayint
