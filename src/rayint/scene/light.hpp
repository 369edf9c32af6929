#pragma once
// External light sources of a scene (Max 1995, Sec. 5-6): a directional light (a distant source:
// parallel beam of irradiance E on a plane perpendicular to it) or a point light (radiant
// intensity I, irradiance I / r^2 at distance r). Neither is attenuated here: shadows (the light's
// optical depth) are applied by the `shadows` effect (scene/shadowing.hpp).
#include <limits>

#include "rayint/geometry/vec3.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct LightArrival {
  Vec3 propagation = Vec3::UnitZ();  // unit direction in which the light travels at p
  double distance = std::numeric_limits<double>::infinity();  // from p to the source
  Rgb irradiance{};                  // unshadowed, on a plane perpendicular to `propagation`
};

struct Light {
  enum class Kind { directional, point };
  Kind kind = Kind::directional;
  Vec3 direction = -Vec3::UnitZ();  // directional: unit direction of propagation
  Vec3 position = Vec3::Zero();     // point light
  Rgb intensity{1.0, 1.0, 1.0};     // directional: irradiance; point: radiant intensity

  LightArrival at(const Vec3& p) const;
};

}  // namespace rayint
