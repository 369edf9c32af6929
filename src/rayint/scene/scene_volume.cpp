// Scene -> ScatteringVolume; see scene_volume.hpp.
#include "rayint/scene/scene_volume.hpp"

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

bool scene_is_grey(const Scene& s) {
  const OpticalTransfer& t = s.medium.transfer();
  const double dmax = s.medium.field().max_density();
  for (int c = 1; c < 3; ++c) {
    if (!same_function(t.extinction[0], t.extinction[c], dmax)) return false;
    if (!same_function(t.albedo[0], t.albedo[c], dmax)) return false;
    for (const Light& l : s.lights)
      if (l.intensity[0] != l.intensity[c]) return false;
  }
  return true;
}

ScatteringVolume volume_from_scene(const Scene& s, int channel, int points) {
  if (points < 2) throw std::invalid_argument("multiple_scattering: points must be >= 2");
  const Bounds b = s.medium.bounds();
  if (!b.finite())
    throw std::invalid_argument(
        "multiple_scattering: the medium must be bounded (for a slab use `rayint slab`)");
  if (s.lights.size() != 1 || s.lights[0].kind != Light::Kind::directional)
    throw std::invalid_argument("multiple_scattering: exactly one directional light is supported");
  const OpticalTransfer& t = s.medium.transfer();
  const std::size_t c = static_cast<std::size_t>(channel);
  const double dmax = s.medium.field().max_density();
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
            s.medium.extinction(p)[c];
      }
  ScatteringVolume v;
  v.density = VoxelGrid({points, points, points}, lo, spacing, std::move(values));
  v.extinction_per_density = 1.0;
  v.albedo = albedo;
  v.phase = s.phase;
  v.light.direction = s.lights[0].direction.normalized();
  v.light.irradiance = s.lights[0].intensity[c];
  v.background = 0.0;
  return v;
}

}  // namespace rayint
