// The `multiple_scattering` scene effect; see multiple_scattering_effect.hpp.
#include "rayint/effects/multiple_scattering_effect.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "rayint/scattering/diffusion.hpp"
#include "rayint/scattering/discrete_ordinates.hpp"
#include "rayint/scattering/scattering_volume.hpp"
#include "rayint/scattering/volume_path_tracer.hpp"
#include "rayint/scattering/zonal.hpp"

namespace rayint {

namespace {

constexpr int kReferenceSpp = 1024;

class MultipleScatteringEffect final : public Effect {
 public:
  explicit MultipleScatteringEffect(const EffectContext& ctx) : spec_(ctx.method) {
    const int points = static_cast<int>(spec_.number("points", 64));
    const int channels = is_grey(ctx.scene.medium, ctx.scene.lights) ? 1 : 3;
    for (int c = 0; c < channels; ++c) {
      volumes_.push_back(volume_from_medium(ctx.scene.medium, ctx.scene.lights, ctx.scene.phase, c, points));
      majorants_.push_back(volumes_.back().majorant());
    }
    if (spec_.name == "discrete_ordinates") {
      DiscreteOrdinatesOptions o;
      o.grid = static_cast<int>(spec_.number("grid", 32));
      o.bins_per_edge = static_cast<int>(spec_.number("bins", 3));
      for (const auto& v : volumes_) ordinates_.push_back(solve_discrete_ordinates(v, o));
    } else if (spec_.name == "zonal") {
      ZonalOptions o;
      o.grid = static_cast<int>(spec_.number("grid", 12));
      for (const auto& v : volumes_) zonal_.push_back(solve_zonal(v, o));
    } else if (spec_.name == "diffusion") {
      DiffusionOptions o;
      o.grid = static_cast<int>(spec_.number("grid", 32));
      for (const auto& v : volumes_) {
        diffusion_.push_back(solve_diffusion(v, o));
        if (!diffusion_.back().converged)
          throw std::runtime_error("multiple_scattering: the diffusion solve did not converge (relative residual " +
                                   std::to_string(diffusion_.back().residual) + ")");
      }
    } else if (spec_.name == "monte_carlo") {
      spp_ = static_cast<int>(spec_.number("spp", 64));
      seed_ = static_cast<std::uint64_t>(spec_.number("seed", 1));
      if (spp_ < 1) throw std::invalid_argument("multiple_scattering: spp must be >= 1");
    } else {
      throw std::invalid_argument("multiple_scattering: unknown method " + spec_.name);
    }
  }
  std::string name() const override { return "multiple_scattering"; }
  std::string method_label() const override { return spec_.label(); }

  Rgb term(const PixelRay& pr, EffectWork& work, EffectWork& shadow_work) const override {
    ++work.rays;
    Rgb out{};
    for (std::size_t c = 0; c < volumes_.size(); ++c) {
      double value = 0;
      if (!ordinates_.empty()) {
        value = gather_discrete_ordinates(volumes_[c], ordinates_[c], pr.ray, false);
      } else if (!diffusion_.empty()) {
        value = gather_diffusion(volumes_[c], diffusion_[c], pr.ray, false);
      } else if (!zonal_.empty()) {
        value = gather_zonal(volumes_[c], zonal_[c], pr.ray, false);
      } else {
        PathTraceStats s;
        value = trace_ray(volumes_[c], pr.ray, spp_, seed_, ray_key(pr.ray), 0, &s, 2, majorants_[c]).mean;
        work.samples += s.tentative_collisions;
        shadow_work.shadow_rays += s.shadow_rays;
      }
      if (volumes_.size() == 1)
        out = {value, value, value};
      else
        out[c] = value;
    }
    return out;
  }

  ReferenceValue reference(const PixelRay& pr) const override {
    ReferenceValue r;
    for (std::size_t c = 0; c < volumes_.size(); ++c) {
      const Estimate e = trace_ray(volumes_[c], pr.ray, kReferenceSpp, 1, ray_key(pr.ray), 0, nullptr, 2,
                                 majorants_[c]);
      const std::size_t lo = volumes_.size() == 1 ? 0 : c, hi = volumes_.size() == 1 ? 3 : c + 1;
      for (std::size_t k = lo; k < hi; ++k) {
        r.value[k] = e.mean;
        r.error_estimate[k] = 2 * e.std_error;
      }
      r.evaluations += kReferenceSpp;
    }
    return r;
  }

 private:
  // A reproducible stream index per ray (its origin and direction bits), so a pixel's estimate
  // does not depend on the order or thread in which rays are evaluated.
  static std::uint64_t ray_key(const ViewRay& ray) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (int a = 0; a < 3; ++a)
      for (double x : {ray.origin[a], ray.direction[a]}) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        h = Rng::splitmix64(h) ^ bits;
      }
    return h;
  }

  MethodSpec spec_;
  std::vector<ScatteringVolume> volumes_;
  std::vector<double> majorants_;
  std::vector<DiscreteOrdinatesSolution> ordinates_;
  std::vector<ZonalSolution> zonal_;
  std::vector<DiffusionSolution> diffusion_;
  int spp_ = 64;
  std::uint64_t seed_ = 1;
};

}  // namespace

std::unique_ptr<Effect> make_multiple_scattering_effect(const EffectContext& ctx) {
  return std::make_unique<MultipleScatteringEffect>(ctx);
}

EffectInfo multiple_scattering_effect_info() {
  return {"multiple_scattering", EffectInfo::Role::term,
          "light scattered two or more times (orders >= 2; src/rayint/scattering/, "
          "docs/multiple-scattering.md)",
          "discrete_ordinates:grid=32:bins=3",
          {{"discrete_ordinates", {"grid", "bins", "points"}, "Max's direction bins on a grid^3 cell grid"},
           {"zonal", {"grid", "points"}, "zonal method, isotropic scattering only"},
           {"diffusion", {"grid", "points"}, "P1 (diffusion) on a grid^3 cell grid, Marshak boundaries"},
           {"monte_carlo", {"spp", "seed", "points"}, "path tracing of orders >= 2"}},
          make_multiple_scattering_effect};
}

}  // namespace rayint
