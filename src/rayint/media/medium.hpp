#pragma once
// The participating medium (Max 1995, Sec. 2-6) that scenes render and the multiple-scattering
// methods resample (scattering/scattering_volume.hpp): a scalar density field in space and
// the transfer functions that turn density into the optical properties every effect uses:
//   extinction sigma_t(p) per unit length (Max's tau, Sec. 2),
//   albedo a(p) in [0, 1], scattering sigma_s = a * sigma_t (Sec. 5),
//   emission source g(p) = kappa(p) * sigma_t(p) per unit length, with kappa the "color" transfer
//   function of Williams & Max (1992, Sec. 3.1) so that the emission-absorption term is exactly the
//   integral the existing integrators/ and reference/ evaluate.
// Each is per colour channel and piecewise linear in density. Outside bounds() the density is 0.
//
// DensityField is the extension point for new medium kinds (homogeneous box and slab here, the
// procedural cloud in scene/cloud.hpp, voxel grids in scene/grid_field.hpp; docs/scenes.md).
#include <array>
#include <limits>
#include <memory>
#include <string>

#include "rayint/geometry/bounds.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/model/ray.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

class DensityField {
 public:
  virtual ~DensityField() = default;
  virtual std::string kind() const = 0;
  virtual Bounds bounds() const = 0;
  // The density at p; 0 outside bounds().
  virtual double density(const Vec3& p) const = 0;
  // An upper bound of density over bounds() (for majorants: delta tracking, Riemann budgets).
  virtual double max_density() const = 0;
  // Gradient of the density (shading). Default: central differences with gradient_step().
  virtual Vec3 gradient(const Vec3& p) const;
  virtual double gradient_step() const { return 1e-3; }
  // The longest stretch of a line on which the density can hold a feature that 15 Gauss-Kronrod
  // nodes spread over it would all miss: the references start every integral from panels no
  // longer than this (QuadratureOptions::panel_length). Infinity for fields smooth on any scale.
  // Measured (tests/test_scene_references.cpp): with the cloud's finest noise wavelength, the
  // view transmittance on rays grazing the cloud matches a 400,000-point midpoint sum to 1e-6
  // (to 9 digits on the probed pixels), where one starting panel was off by 0.12.
  virtual double feature_length() const = 0;
  // True when the density is piecewise linear along every straight line (homogeneous media,
  // Kuhn-tetrahedralized grids); then linear_segments() gives the ray inside bounds as model
  // segments, far -> near, so that integrators/exact and reference/ apply unchanged.
  virtual bool piecewise_linear() const { return false; }
  virtual Ray linear_segments(const ViewRay& ray, const Rgb& background) const;
};

// Constant density inside a box, or inside a slab z in [z_bottom, z_top] unbounded in x and y.
class HomogeneousField final : public DensityField {
 public:
  HomogeneousField(double density, Bounds bounds, bool slab);
  std::string kind() const override { return slab_ ? "homogeneous slab" : "homogeneous box"; }
  Bounds bounds() const override { return bounds_; }
  double density(const Vec3& p) const override { return bounds_.contains(p) ? density_ : 0.0; }
  double max_density() const override { return density_; }
  Vec3 gradient(const Vec3&) const override { return Vec3::Zero(); }
  // Constant on the span clipped to the bounds: one panel suffices.
  double feature_length() const override { return std::numeric_limits<double>::infinity(); }
  bool piecewise_linear() const override { return true; }
  Ray linear_segments(const ViewRay& ray, const Rgb& background) const override;
  bool slab() const { return slab_; }

 private:
  double density_;
  Bounds bounds_;
  bool slab_;
};

// Density -> optical properties (per channel, piecewise linear, constant beyond the end points).
struct OpticalTransfer {
  std::array<PiecewiseLinear, kChannels> extinction;  // sigma_t, >= 0
  std::array<PiecewiseLinear, kChannels> albedo;      // in [0, 1]
  std::array<PiecewiseLinear, kChannels> emission;    // kappa: source g = kappa * sigma_t
  // The six functions of Williams & Max for the emission-absorption integrators: rho = sigma_t,
  // and kappa = emission (or 0 for absorption only).
  TransferFunctions emission_absorption(bool with_emission = true) const;
  // The largest extinction over densities in [0, max_density], per channel.
  Rgb max_extinction(double max_density) const;
};

struct Optics {
  Rgb sigma_t{};
  Rgb albedo{};
  Rgb kappa{};
};

class Medium {
 public:
  Medium() = default;
  Medium(std::shared_ptr<const DensityField> field, OpticalTransfer transfer);

  const DensityField& field() const { return *field_; }
  const OpticalTransfer& transfer() const { return transfer_; }
  Bounds bounds() const { return field_->bounds(); }

  double density(const Vec3& p) const { return field_->density(p); }
  Optics optics_at_density(double d) const;
  Rgb extinction(const Vec3& p) const;
  Rgb albedo(const Vec3& p) const;
  Rgb scattering(const Vec3& p) const;  // albedo * extinction
  Rgb emission(const Vec3& p) const;    // kappa * extinction
  // Max extinction over the bounds, per channel (for delta / ratio tracking).
  Rgb majorant() const { return majorant_; }

 private:
  std::shared_ptr<const DensityField> field_;
  OpticalTransfer transfer_;
  Rgb majorant_{};
};

}  // namespace rayint
