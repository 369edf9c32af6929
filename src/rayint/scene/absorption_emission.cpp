#include "rayint/scene/absorption_emission.hpp"

#include <stdexcept>

#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/scene/grid_field.hpp"
#include "rayint/scene/term_references.hpp"
#include "rayint/media/riemann_march.hpp"

namespace rayint {
namespace {

const GridField* trilinear_grid(const DensityField& field) {
  const auto* g = dynamic_cast<const GridField*>(&field);
  return g != nullptr && g->interpolation() == GridInterpolation::trilinear ? g : nullptr;
}

// Shared by both terms: method exact (integrators/exact, refused unless the medium is piecewise
// linear along rays) or riemann:n, on the emission-absorption transfer functions.
class ExactOrRiemannEffect : public Effect {
 public:
  ExactOrRiemannEffect(const EffectContext& ctx, const char* effect, bool emission)
      : scene_(ctx.scene), spec_(ctx.method), name_(effect),
        tf_(ctx.scene.medium.transfer().emission_absorption(emission)) {
    if (ctx.method.name == "exact" && !exact_along_rays(ctx.scene.medium.field()))
      throw std::invalid_argument(std::string(effect) +
                                  ": method exact needs a medium that is piecewise "
                                  "linear along rays (homogeneous or grid), not " +
                                  ctx.scene.medium.field().kind() + "; use riemann:n=N");
    exact_ = spec_.name == "exact";
    trilinear_ = trilinear_grid(ctx.scene.medium.field());
    if (exact_ && trilinear_ != nullptr) trilinear_integrator_ = std::make_unique<TrilinearIntegrator>(tf_);
    else if (exact_) integrator_ = std::make_unique<ExactIntegrator>(tf_);
    else n_ = riemann_samples(spec_);
  }
  std::string name() const override { return name_; }
  std::string method_label() const override { return spec_.label(); }

 protected:
  const Scene& scene_;
  MethodSpec spec_;
  const char* name_;
  TransferFunctions tf_;
  bool exact_ = false;
  int n_ = 0;
  std::unique_ptr<ExactIntegrator> integrator_;
  // A trilinear voxel grid: exact is grid/trilinear_integral, the reference reference_poly_ray.
  // Rays go to the grid's own frame first (GridField::to_grid: a rotated image).
  const GridField* trilinear_ = nullptr;
  std::unique_ptr<TrilinearIntegrator> trilinear_integrator_;
};

class AbsorptionEffect final : public ExactOrRiemannEffect {
 public:
  explicit AbsorptionEffect(const EffectContext& ctx)
      : ExactOrRiemannEffect(ctx, "absorption", false) {}

  Rgb term(const PixelRay& pr, EffectWork& work, EffectWork&) const override {
    ++work.rays;
    Rgb T;
    if (exact_ && trilinear_ != nullptr) {
      const TrilinearRayResult r = trilinear_integrator_->integrate(trilinear_->grid(), trilinear_->to_grid(pr.ray), Rgb{});
      work.samples += r.pieces;
      T = r.transmittance;
    } else if (exact_) {
      const Ray ray = scene_.medium.field().linear_segments(pr.ray, Rgb{});
      work.samples += static_cast<long long>(ray.segments.size());
      T = integrator_->integrate(ray, nullptr).transmittance;
    } else {
      T = riemann_transmittance(scene_.medium, pr.ray, n_, work.samples);
    }
    return {pr.background[0] * T[0], pr.background[1] * T[1], pr.background[2] * T[2]};
  }

  ReferenceValue reference(const PixelRay& pr) const override {
    ReferenceValue r;
    if (trilinear_ != nullptr || scene_.medium.field().piecewise_linear()) {
      const ReferenceRay ref = trilinear_ != nullptr
                                   ? reference_poly_ray(tf_, trilinear_ray(trilinear_->grid(), trilinear_->to_grid(pr.ray), Rgb{}))
                                   : reference_ray(tf_, scene_.medium.field().linear_segments(pr.ray, Rgb{}));
      for (int c = 0; c < kChannels; ++c) {
        r.value[c] = ref.transmittance[c].hi;
        r.error_estimate[c] = 1e-30;  // 50-digit arithmetic
      }
      r.evaluations = ref.subintervals;
    } else {
      r = reference_transmittance(scene_, pr.ray);
    }
    for (int c = 0; c < kChannels; ++c) {
      r.value[c] *= pr.background[c];
      r.error_estimate[c] *= pr.background[c];
    }
    return r;
  }
};

class EmissionEffect final : public ExactOrRiemannEffect {
 public:
  explicit EmissionEffect(const EffectContext& ctx)
      : ExactOrRiemannEffect(ctx, "emission", true), absorption_(ctx.absorption) {}

  Rgb term(const PixelRay& pr, EffectWork& work, EffectWork&) const override {
    ++work.rays;
    if (exact_ && trilinear_ != nullptr) {
      if (!absorption_) return trilinear_integrator_->emission_only(trilinear_->grid(), trilinear_->to_grid(pr.ray));
      const TrilinearRayResult r = trilinear_integrator_->integrate(trilinear_->grid(), trilinear_->to_grid(pr.ray), Rgb{});
      work.samples += r.pieces;
      return r.intensity;
    }
    if (exact_) {
      const Ray ray = scene_.medium.field().linear_segments(pr.ray, Rgb{});
      work.samples += static_cast<long long>(ray.segments.size());
      return absorption_ ? integrator_->integrate(ray, nullptr).intensity : emission_only_exact(tf_, ray);
    }
    return riemann_march(scene_.medium, pr.ray, n_, absorption_,
                         [](const Vec3&, const Optics& o) {
                           return Rgb{o.kappa[0] * o.sigma_t[0], o.kappa[1] * o.sigma_t[1], o.kappa[2] * o.sigma_t[2]};
                         },
                         work.samples);
  }

  ReferenceValue reference(const PixelRay& pr) const override {
    if (absorption_ && (trilinear_ != nullptr || scene_.medium.field().piecewise_linear())) {
      ReferenceValue r;
      const ReferenceRay ref = trilinear_ != nullptr
                                   ? reference_poly_ray(tf_, trilinear_ray(trilinear_->grid(), trilinear_->to_grid(pr.ray), Rgb{}))
                                   : reference_ray(tf_, scene_.medium.field().linear_segments(pr.ray, Rgb{}));
      for (int c = 0; c < kChannels; ++c) {
        r.value[c] = ref.intensity[c].hi;
        r.error_estimate[c] = ref.error_bound[c];
      }
      r.evaluations = ref.subintervals;
      return r;
    }
    return reference_source_term(
        scene_, pr.ray,
        [](const Vec3&, const Optics& o, const LightTransmittanceFn&) {
          return Rgb{o.kappa[0] * o.sigma_t[0], o.kappa[1] * o.sigma_t[1], o.kappa[2] * o.sigma_t[2]};
        },
        absorption_, false);
  }

 private:
  bool absorption_;
};

}  // namespace

Rgb emission_only_exact(const TransferFunctions& tf, const Ray& ray) {
  Rgb sum{};
  for (const Piece& p : split_ray(tf, ray))
    for (int c = 0; c < kChannels; ++c) {
      // kappa and rho linear on the piece: int kappa rho = L (2 kf rf + 2 ke re + kf re + ke rf) / 6
      const double kf = p.kappa_far[c], ke = p.kappa_exit[c], rf = p.rho_far[c], re = p.rho_exit[c];
      sum[c] += p.length * (2.0 * kf * rf + 2.0 * ke * re + kf * re + ke * rf) / 6.0;
    }
  return sum;
}

std::unique_ptr<Effect> make_absorption_effect(const EffectContext& context) {
  return std::make_unique<AbsorptionEffect>(context);
}
std::unique_ptr<Effect> make_emission_effect(const EffectContext& context) {
  return std::make_unique<EmissionEffect>(context);
}

}  // namespace rayint
