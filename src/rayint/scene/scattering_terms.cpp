#include "rayint/scene/scattering_terms.hpp"

#include <cmath>
#include <stdexcept>

#include "rayint/scene/term_references.hpp"
#include "rayint/media/riemann_march.hpp"
#include "rayint/scene/shadowing.hpp"

namespace rayint {
namespace {

// Shared by both terms: a per-point source with a light-transmittance callback.
class LitTermEffect : public Effect {
 public:
  LitTermEffect(const EffectContext& ctx, std::string name)
      : scene_(ctx.scene), spec_(ctx.method), name_(std::move(name)), absorption_(ctx.absorption),
        shadows_(ctx.shadows), shadowing_(ctx.shadowing) {
    if (spec_.name != "riemann")
      throw std::invalid_argument(name_ + ": unknown method " + spec_.name + " (expected riemann:n=N)");
    n_ = riemann_samples(spec_);
  }
  std::string name() const override { return name_; }
  std::string method_label() const override { return spec_.label(); }

  Rgb term(const PixelRay& pr, EffectWork& work, EffectWork& shadow_work) const override {
    ++work.rays;
    const LightTransmittanceFn tl = [&](std::size_t l, const Vec3& p) {
      return shadowing_->transmittance(l, p, shadow_work);
    };
    return riemann_march(scene_.medium, pr.ray, n_, absorption_,
                         [&](const Vec3& p, const Optics& o) { return source(p, o, pr.ray.direction, tl); },
                         work.samples);
  }

  ReferenceValue reference(const PixelRay& pr) const override {
    const Vec3 d = pr.ray.direction;
    return reference_source_term(
        scene_, pr.ray,
        [&](const Vec3& p, const Optics& o, const LightTransmittanceFn& tl) { return source(p, o, d, tl); },
        absorption_, shadows_);
  }

 protected:
  virtual Rgb source(const Vec3& p, const Optics& o, const Vec3& view_dir,
                     const LightTransmittanceFn& tl) const = 0;
  const Scene& scene_;

 private:
  MethodSpec spec_;
  std::string name_;
  bool absorption_, shadows_;
  const Shadowing* shadowing_;
  int n_ = 0;
};

class SingleScatteringEffect final : public LitTermEffect {
 public:
  explicit SingleScatteringEffect(const EffectContext& ctx) : LitTermEffect(ctx, "single_scattering") {}

 protected:
  Rgb source(const Vec3& p, const Optics& o, const Vec3& view_dir,
             const LightTransmittanceFn& tl) const override {
    Rgb sigma_s{};
    bool any = false;
    for (int c = 0; c < kChannels; ++c) {
      sigma_s[c] = o.albedo[c] * o.sigma_t[c];
      any = any || sigma_s[c] > 0.0;
    }
    Rgb S{};
    if (!any) return S;  // nothing scatters here: no light is looked up, no shadow ray cast
    for (std::size_t l = 0; l < scene_.lights.size(); ++l) {
      const LightArrival a = scene_.lights[l].at(p);
      const double phase = scene_.phase.eval(a.propagation.dot(-view_dir));
      const Rgb T = tl(l, p);
      for (int c = 0; c < kChannels; ++c) S[c] += sigma_s[c] * phase * a.irradiance[c] * T[c];
    }
    return S;
  }
};

class ShadingEffect final : public LitTermEffect {
 public:
  explicit ShadingEffect(const EffectContext& ctx) : LitTermEffect(ctx, "shading") {}

 protected:
  Rgb source(const Vec3& p, const Optics&, const Vec3& view_dir,
             const LightTransmittanceFn& tl) const override {
    Rgb S{};
    const Vec3 g = scene_.medium.field().gradient(p);
    const double strength = scene_.shading.strength * g.norm();
    if (!(strength > 0.0)) return S;
    const Vec3 N = -g.normalized();
    const Vec3 V = -view_dir;
    const ShadingParams& sp = scene_.shading;
    for (std::size_t l = 0; l < scene_.lights.size(); ++l) {
      const LightArrival a = scene_.lights[l].at(p);
      const Vec3 L = -a.propagation;
      const double ndotl = N.dot(L);
      if (!(ndotl > 0.0)) continue;
      const Vec3 R = 2.0 * ndotl * N - L;
      const double spec = std::pow(std::max(0.0, R.dot(V)), sp.shininess);
      const Rgb T = tl(l, p);
      for (int c = 0; c < kChannels; ++c)
        S[c] += strength * (sp.diffuse[c] * ndotl + sp.specular[c] * spec) * a.irradiance[c] * T[c];
    }
    return S;
  }
};

}  // namespace

std::unique_ptr<Effect> make_single_scattering_effect(const EffectContext& context) {
  return std::make_unique<SingleScatteringEffect>(context);
}
std::unique_ptr<Effect> make_shading_effect(const EffectContext& context) {
  return std::make_unique<ShadingEffect>(context);
}

}  // namespace rayint
