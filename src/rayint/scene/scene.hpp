#pragma once
// A scene (format: docs/scenes.md; reader: input/scene_reader.hpp): the medium, lights, phase
// function, a camera or explicit rays, the background, and the effects it asks for, each with the
// method that computes it. The pipeline (scene/pipeline.hpp) evaluates exactly those effects.
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <limits>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"  // MethodSpec
#include "rayint/optics/phase.hpp"
#include "rayint/geometry/camera.hpp"
#include "rayint/render/image.hpp"
#include "rayint/media/light.hpp"
#include "rayint/media/medium.hpp"

namespace rayint {

// What enters a viewing ray at its far end: a constant colour, or an image behind the medium
// mapped to the camera's pixels (Max's aerial photograph behind the cloud).
struct Background {
  Rgb color{0.0, 0.0, 0.0};
  std::shared_ptr<const Image> image;  // null: constant colour
  // At normalized image coordinates (u, v) in [0, 1]^2, v = 0 at the top.
  Rgb at(double u, double v) const { return image ? image->sample(u, v) : color; }
};

// Max's gradient-strength surface shading (1995, Sec. 5): the source term
//   strength * |grad rho| * (diffuse * max(0, N.L) + specular * max(0, R.V)^shininess) * E
// with N = -grad rho / |grad rho| (pointing toward lower density), L toward the light, V toward
// the eye and R the mirror direction of L about N (Lambert when specular = 0, else Phong).
struct ShadingParams {
  Rgb diffuse{1.0, 1.0, 1.0};
  Rgb specular{0.0, 0.0, 0.0};
  double shininess = 20.0;
  double strength = 1.0;
};

struct QuadratureOptions {
  double rtol = 1e-9;            // relative tolerance of every adaptive integral
  double atol = 1e-14;           // absolute floor
  int max_intervals = 4000;      // subintervals per integral before it reports non-convergence
  // Each integral starts from panels no longer than this (the medium's feature_length()): a
  // single Gauss-Kronrod panel whose 15 nodes all miss a feature reports a zero error estimate
  // and "converges" to the wrong value (seen: a ray clipping the cloud's edge got T = 1 against
  // a true 0.88). Infinity: one starting panel.
  double panel_length = std::numeric_limits<double>::infinity();
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;  // file it was read from (messages)
  Medium medium;
  std::vector<Light> lights;
  PhaseFunction phase = PhaseFunction::isotropic();
  std::optional<Camera> camera;  // exactly one of camera / rays
  std::vector<ViewRay> rays;
  Background background;
  std::vector<std::string> effects;            // as listed; validated against the registry
  std::map<std::string, MethodSpec> methods;   // per effect; missing: the effect's default
  std::map<std::string, nlohmann::json> settings;  // per effect, raw (registered effects)
  ShadingParams shading;
  QuadratureOptions reference;

  bool has(const std::string& effect) const;
};

}  // namespace rayint
