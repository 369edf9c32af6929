#include "rayint/scene/absorption_emission.hpp"

#include <stdexcept>
#include <utility>

#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/nerf.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/scene/grid_field.hpp"
#include "rayint/scene/term_references.hpp"
#include "rayint/media/riemann_march.hpp"

namespace rayint {
namespace {

// NeRF's quadrature along the ray's span inside the bounds (Mildenhall et al. 2020, Eq. 3;
// integrators/nerf.hpp): n intervals of length delta = span / n, one sample each at the interval's
// midpoint (offset 0.5) or eye-side end (offset 0, NeRF 2020's t_i), colour kappa and density
// sigma held over the interval: C = sum_i T_i alpha_i kappa_i, alpha_i = 1 - exp(-sigma_i delta),
// T_i = prod_{j<i} (1 - alpha_j) (FrontToBack). Returns (C, T after the last interval); without
// `attenuate` the emission is sum_i kappa_i sigma_i delta. At offset 0.5 it is the same sum as
// riemann_march's (S alpha / sigma with S = kappa sigma) by a different evaluation; at offset 0
// the rule is first order (tests [converge]).
std::pair<Rgb, Rgb> nerf_march(const Medium& medium, const ViewRay& ray, int n, double offset, bool attenuate,
                               long long& samples) {
  Rgb C{}, T{1.0, 1.0, 1.0};
  const RaySpan span = medium.bounds().clip(ray);
  if (!span.hit || n < 1) return {C, T};
  const double delta = span.length() / n;
  FrontToBack f[kChannels];
  for (int i = 0; i < n; ++i) {
    const Vec3 p = ray.origin + ray.direction * (span.t_enter + (i + offset) * delta);
    const Optics o = medium.optics_at_density(medium.density(p));
    for (int c = 0; c < kChannels; ++c) {
      const auto k = static_cast<std::size_t>(c);
      if (attenuate) f[k].add(o.sigma_t[k] * delta, o.kappa[k]);
      else C[k] += o.kappa[k] * o.sigma_t[k] * delta;
    }
  }
  samples += n;
  if (attenuate)
    for (std::size_t c = 0; c < static_cast<std::size_t>(kChannels); ++c) {
      C[c] = f[c].emission;
      T[c] = f[c].transmittance;
    }
  return {C, T};
}

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
    nerf_ = spec_.name == "nerf";
    nerf_offset_ = spec_.text("at", "mid") == "near" ? 0.0 : 0.5;
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
  bool nerf_ = false;          // nerf:n:at (nerf_march), else riemann:n
  double nerf_offset_ = 0.5;   // the sample's place in its interval: 0.5 mid, 0 near
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
    } else if (nerf_) {
      T = nerf_march(scene_.medium, pr.ray, n_, nerf_offset_, true, work.samples).second;
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
    if (nerf_) return nerf_march(scene_.medium, pr.ray, n_, nerf_offset_, absorption_, work.samples).first;
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
