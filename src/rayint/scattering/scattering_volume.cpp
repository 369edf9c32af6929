// The scattering medium on a voxel grid; see scattering_volume.hpp.
#include "rayint/scattering/scattering_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rayint {

double ScatteringVolume::sigma_t(const Vec3& x) const {
  const Vec3 lo = density.lower(), hi = density.upper();
  for (int a = 0; a < 3; ++a)
    if (x[a] < lo[a] || x[a] > hi[a]) return 0.0;
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
