#pragma once
// Shadows (Max 1995, Sec. 6): the fraction of a light's irradiance that reaches a point p inside
// the medium, T_L(p) = exp(-int_0^{s_L} sigma_t(p - s w) ds) along the light's path (w its
// propagation direction, s_L the distance to the medium's boundary or to a point light).
//
// Three ways, all behind one interface so that single scattering and shading never know which:
//   - NoShadows: T_L = 1 and no work (the scene does not name `shadows`).
//   - ShadowRays ("shadow_rays:n=N"): a shadow ray from p toward the light, N midpoint samples
//     over its length inside the bounds, T_L = exp(-sum sigma h) (Riemann sum of the depth).
//   - LightGrid ("two_pass:grid=R"): Kajiya & Von Herzen's first pass. T_L is computed once on
//     the vertices of an R^3 grid over the bounds and trilinearly interpolated in the gathering
//     pass. For a directional light the flux is propagated layer by layer along the axis most
//     aligned with the light: each vertex takes the bilinearly interpolated transmittance of the
//     previous layer where its light path crosses it, times exp(-h (sigma(q) + sigma(v)) / 2)
//     (trapezoid over the step h between the layers): O(R^3) work. A point light gets one
//     shadow ray per vertex with steps of the grid spacing (O(R^4)).
// The reference (nested adaptive quadrature of the light depth) is in scene/term_references.hpp.
#include <memory>
#include <string>
#include <vector>

#include "rayint/scene/effect.hpp"

namespace rayint {

class Shadowing {
 public:
  virtual ~Shadowing() = default;
  virtual std::string label() const = 0;
  // Transmittance from light `light` (index into scene.lights) to p. Thread-safe.
  virtual Rgb transmittance(std::size_t light, const Vec3& p, EffectWork& work) const = 0;
  virtual double setup_seconds() const { return 0.0; }
  virtual double setup_cpu_seconds() const { return 0.0; }
};

class NoShadows final : public Shadowing {
 public:
  std::string label() const override { return "none"; }
  Rgb transmittance(std::size_t, const Vec3&, EffectWork&) const override { return {1.0, 1.0, 1.0}; }
};

class ShadowRays final : public Shadowing {
 public:
  ShadowRays(const Scene& scene, int n);
  std::string label() const override { return "shadow_rays:n=" + std::to_string(n_); }
  Rgb transmittance(std::size_t light, const Vec3& p, EffectWork& work) const override;

 private:
  const Scene& scene_;
  int n_;
};

class LightGrid final : public Shadowing {
 public:
  // Throws std::invalid_argument for unbounded media (a slab): the grid needs finite bounds.
  LightGrid(const Scene& scene, int resolution, unsigned threads);
  std::string label() const override { return "two_pass:grid=" + std::to_string(res_); }
  Rgb transmittance(std::size_t light, const Vec3& p, EffectWork& work) const override;
  double setup_seconds() const override { return setup_seconds_; }
  double setup_cpu_seconds() const override { return setup_cpu_seconds_; }
  long long setup_samples() const { return setup_samples_; }

 private:
  void propagate_directional(std::size_t light);
  void march_point(std::size_t light, unsigned threads);
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(res_) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(res_) * static_cast<std::size_t>(k));
  }
  Vec3 vertex(int i, int j, int k) const;
  const Scene& scene_;
  int res_;
  Vec3 lower_, spacing_;
  std::vector<std::vector<Rgb>> grids_;  // per light
  double setup_seconds_ = 0.0;
  double setup_cpu_seconds_ = 0.0;
  long long setup_samples_ = 0;
};

// The Shadowing of a scene: NoShadows unless `shadows` is named; then the method in
// scene.methods["shadows"] (default shadow_rays with the single-scattering n).
std::unique_ptr<Shadowing> make_shadowing(const Scene& scene, unsigned threads);

// Where a light's path from p leaves the medium (or reaches a point light): the distance along
// -propagation, 0 if p is outside.
double light_path_length(const Scene& scene, const Vec3& p, const LightArrival& arrival);

}  // namespace rayint
