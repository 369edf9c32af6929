// Light sources; see light.hpp.
#include "rayint/media/light.hpp"

#include <cmath>

namespace rayint {

LightArrival Light::at(const Vec3& p) const {
  LightArrival a;
  if (kind == Kind::directional) {
    a.propagation = direction;
    a.irradiance = intensity;
    return a;
  }
  const Vec3 d = p - position;
  const double r2 = d.squaredNorm();
  a.distance = std::sqrt(r2);
  a.propagation = a.distance > 0.0 ? Vec3(d / a.distance) : Vec3::UnitZ();
  for (int c = 0; c < kChannels; ++c) a.irradiance[c] = r2 > 0.0 ? intensity[c] / r2 : 0.0;
  return a;
}

DirectionalLight Light::channel(int c) const {
  return {direction.normalized(), intensity[static_cast<std::size_t>(c)]};
}

}  // namespace rayint
