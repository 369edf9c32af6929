// The medium of scenes and volumes; see medium.hpp.
#include "rayint/media/medium.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rayint {

Vec3 DensityField::gradient(const Vec3& p) const {
  const double h = gradient_step();
  Vec3 g;
  for (int a = 0; a < 3; ++a) {
    Vec3 e = Vec3::Zero();
    e[a] = h;
    g[a] = (density(p + e) - density(p - e)) / (2.0 * h);
  }
  return g;
}

Ray DensityField::linear_segments(const ViewRay&, const Rgb&) const {
  throw std::logic_error(kind() + " is not piecewise linear along rays");
}

HomogeneousField::HomogeneousField(double density, Bounds bounds, bool slab)
    : density_(density), bounds_(bounds), slab_(slab) {}

Ray HomogeneousField::linear_segments(const ViewRay& ray, const Rgb& background) const {
  Ray out;
  out.background = background;
  const RaySpan span = bounds_.clip(ray);
  if (span.hit) out.segments.push_back({span.length() * ray.direction.norm(), density_, density_});
  return out;
}

TransferFunctions OpticalTransfer::emission_absorption(bool with_emission) const {
  TransferFunctions tf;
  tf.density = extinction;
  for (int c = 0; c < kChannels; ++c)
    tf.color[c] = with_emission ? emission[c] : PiecewiseLinear{{0.0}, {0.0}};
  return tf;
}

Rgb OpticalTransfer::max_extinction(double max_density) const {
  Rgb out{};
  for (int c = 0; c < kChannels; ++c) {
    const PiecewiseLinear& f = extinction[c];
    double m = std::max(f(0.0), f(max_density));
    for (std::size_t i = 0; i < f.scalar.size(); ++i)
      if (f.scalar[i] >= 0.0 && f.scalar[i] <= max_density) m = std::max(m, f.value[i]);
    out[c] = m;
  }
  return out;
}

Medium::Medium(std::shared_ptr<const DensityField> field, OpticalTransfer transfer)
    : field_(std::move(field)), transfer_(std::move(transfer)) {
  majorant_ = transfer_.max_extinction(field_->max_density());
}

Optics Medium::optics_at_density(double d) const {
  Optics o;
  for (int c = 0; c < kChannels; ++c) {
    o.sigma_t[c] = transfer_.extinction[c](d);
    o.albedo[c] = transfer_.albedo[c](d);
    o.kappa[c] = transfer_.emission[c](d);
  }
  return o;
}

Rgb Medium::extinction(const Vec3& p) const { return optics_at_density(density(p)).sigma_t; }
Rgb Medium::albedo(const Vec3& p) const { return optics_at_density(density(p)).albedo; }
Rgb Medium::scattering(const Vec3& p) const {
  const Optics o = optics_at_density(density(p));
  return {o.albedo[0] * o.sigma_t[0], o.albedo[1] * o.sigma_t[1], o.albedo[2] * o.sigma_t[2]};
}
Rgb Medium::emission(const Vec3& p) const {
  const Optics o = optics_at_density(density(p));
  return {o.kappa[0] * o.sigma_t[0], o.kappa[1] * o.sigma_t[1], o.kappa[2] * o.sigma_t[2]};
}

}  // namespace rayint
