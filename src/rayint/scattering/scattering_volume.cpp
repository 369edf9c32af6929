// The scattering medium on a voxel grid, and its resampling from a medium; see
// scattering_volume.hpp.
#include "rayint/scattering/scattering_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rayint {

namespace {

bool same_function(const PiecewiseLinear& a, const PiecewiseLinear& b, double max_density) {
  for (int i = 0; i <= 64; ++i) {
    const double d = max_density * i / 64.0;
    if (a(d) != b(d)) return false;
  }
  return true;
}

}  // namespace

bool is_grey(const Medium& medium, const std::vector<Light>& lights) {
  const OpticalTransfer& t = medium.transfer();
  const double dmax = medium.field().max_density();
  for (int c = 1; c < 3; ++c) {
    if (!same_function(t.extinction[0], t.extinction[c], dmax)) return false;
    if (!same_function(t.albedo[0], t.albedo[c], dmax)) return false;
    for (const Light& l : lights)
      if (l.intensity[0] != l.intensity[c]) return false;
  }
  return true;
}

ScatteringVolume volume_from_medium(const Medium& medium, const std::vector<Light>& lights,
                                    const PhaseFunction& phase, int channel, int points) {
  if (points < 2) throw std::invalid_argument("multiple_scattering: points must be >= 2");
  const Bounds b = medium.bounds();
  if (!b.finite())
    throw std::invalid_argument(
        "multiple_scattering: the medium must be bounded (for a slab use `rayint slab`)");
  if (lights.size() != 1 || lights[0].kind != Light::Kind::directional)
    throw std::invalid_argument("multiple_scattering: exactly one directional light is supported");
  const OpticalTransfer& t = medium.transfer();
  const std::size_t c = static_cast<std::size_t>(channel);
  const double dmax = medium.field().max_density();
  const double albedo = t.albedo[c](0.0);
  for (int i = 0; i <= 64; ++i)
    if (t.albedo[c](dmax * i / 64.0) != albedo)
      throw std::invalid_argument("multiple_scattering: the albedo must not depend on density");
  const Vec3 lo = b.lower, hi = b.upper;
  const Vec3 spacing = (hi - lo) / (points - 1);
  std::vector<double> values(static_cast<std::size_t>(points) * points * points);
  for (int k = 0; k < points; ++k)
    for (int j = 0; j < points; ++j)
      for (int i = 0; i < points; ++i) {
        const Vec3 p = lo + Vec3(i * spacing[0], j * spacing[1], k * spacing[2]);
        values[static_cast<std::size_t>(i) +
               static_cast<std::size_t>(points) * (static_cast<std::size_t>(j) +
                                                   static_cast<std::size_t>(points) * k)] =
            medium.extinction(p)[c];
      }
  ScatteringVolume v;
  v.density = VoxelGrid({points, points, points}, lo, spacing, std::move(values));
  v.extinction_per_density = 1.0;
  v.albedo = albedo;
  v.phase = phase;
  v.light = lights[0].channel(channel);
  v.background = 0.0;
  return v;
}

double ScatteringVolume::sigma_t(const Vec3& x) const {
  if (!density.bounds().contains(x)) return 0.0;
  return extinction_per_density * density.sample(x);
}

double ScatteringVolume::majorant() const {
  const auto& v = density.values();
  return extinction_per_density * *std::max_element(v.begin(), v.end());
}

void ScatteringVolume::validate() const {
  auto bad = [](const char* what) { throw std::invalid_argument(what); };
  if (!(extinction_per_density >= 0 && std::isfinite(extinction_per_density)))
    bad("scattering volume: extinction_per_density must be finite and >= 0");
  if (!(albedo >= 0 && albedo <= 1)) bad("scattering volume: albedo must be in [0, 1]");
  for (double v : density.values())
    if (!(v >= 0 && std::isfinite(v))) bad("scattering volume: density values must be finite and >= 0");
  if (!(std::fabs(light.direction.norm() - 1) < 1e-9)) bad("scattering volume: light direction must be a unit vector");
  if (!(light.irradiance >= 0 && std::isfinite(light.irradiance)))
    bad("scattering volume: light irradiance must be finite and >= 0");
  if (!(background >= 0 && std::isfinite(background))) bad("scattering volume: background must be finite and >= 0");
}

}  // namespace rayint
