#pragma once
// External light sources (Max 1995, Sec. 5-6): a directional light (a distant source: parallel
// beam of irradiance E on a plane perpendicular to it) or a point light (radiant intensity I,
// irradiance I / r^2 at distance r). Neither is attenuated here: in scenes shadows (the light's
// optical depth) are applied by the `shadows` effect (scene/shadowing.hpp); the multiple-scattering
// solvers (scattering/) take one channel of a directional light, DirectionalLight.
#include <limits>

#include "rayint/geometry/vec3.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct LightArrival {
  Vec3 propagation = Vec3::UnitZ();  // unit direction in which the light travels at p
  double distance = std::numeric_limits<double>::infinity();  // from p to the source
  Rgb irradiance{};                  // unshadowed, on a plane perpendicular to `propagation`
};

// One colour channel of a directional light: the form the multiple-scattering solvers take
// (scattering/scattering_volume.hpp).
struct DirectionalLight {
  Vec3 direction = Vec3(0, 0, -1);  // direction of propagation (unit)
  double irradiance = 1.0;          // on a plane perpendicular to `direction`
};

struct Light {
  enum class Kind { directional, point };
  Kind kind = Kind::directional;
  Vec3 direction = -Vec3::UnitZ();  // directional: unit direction of propagation
  Vec3 position = Vec3::Zero();     // point light
  Rgb intensity{1.0, 1.0, 1.0};     // directional: irradiance; point: radiant intensity

  LightArrival at(const Vec3& p) const;
  // Channel c of a directional light, its direction normalized (the caller checks the kind).
  DirectionalLight channel(int c) const;
};

}  // namespace rayint
