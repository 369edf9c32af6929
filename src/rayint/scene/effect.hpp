#pragma once
// The effect interface and registry: how a scene's "effects" become a pipeline.
//
// An effect contributes one *term* to the light reaching the eye along each viewing ray; a pixel
// is the sum of the terms (plus the unattenuated background when `absorption` is not named).
// Two effects are *modifiers* of the others rather than terms of their own:
//   - absorption: the medium's extinction along the viewing ray. Its term is the background seen
//     through the medium, B * T; every other term is attenuated by T when it is named, and not at
//     all otherwise (Max's emission-only model, Sec. 3);
//   - shadows: the light's optical depth to each scattering point (Sec. 6), applied by the
//     single_scattering and shading terms through a Shadowing (scene/shadowing.hpp). It has no
//     term; its work (shadow rays, light-grid pass) is reported under its own name.
// A term no named effect asks for is never evaluated; adding a term effect never changes
// another's term (each is integrated on its own samples; tests/test_scene_pipeline.cpp).
//
// To add an effect: implement Effect in its own file and describe it by an EffectInfo. An effect
// that needs only scene/ and the areas below it is built in: one EffectInfo line in registry() in
// scene/effect_registry.cpp. An effect implemented by an area scene/ does not link (as
// `multiple_scattering` by scattering/) lives in src/rayint/effects/ and registers itself with
// register_effect() from register_standard_effects() (effects/standard_effects.hpp), the one
// registration call that the CLI's main and the tests' main make before any scene is read, so
// both see the same registry. Its name is reserved in registry() at its place in the pipeline
// order, so a program that never calls register_standard_effects() is told to, rather than
// getting "unknown effect". docs/scenes.md describes the contract.
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rayint/scene/scene.hpp"

namespace rayint {

class Shadowing;

// Work done by one effect, summed over threads and rays.
struct EffectWork {
  double seconds = 0.0;        // wall time in this effect's per-ray work (summed over threads)
  double cpu_seconds = 0.0;    // CPU time of the same work (thread CPU clocks, summed)
  double setup_seconds = 0.0;  // one-time work before the rays (e.g. the two-pass light grid)
  double setup_cpu_seconds = 0.0;
  long long rays = 0;          // viewing rays evaluated
  long long samples = 0;       // medium samples along viewing rays
  long long shadow_rays = 0;   // rays cast toward a light
  long long shadow_samples = 0;
  long long lookups = 0;       // light-grid lookups (two-pass)
  void add(const EffectWork& o);
};

// One viewing ray and the background radiance entering it at the far end.
struct PixelRay {
  ViewRay ray;
  Rgb background{};
};

// A reference value of a term with the integrator's own error estimate.
struct ReferenceValue {
  Rgb value{};
  Rgb error_estimate{};  // absolute
  long long evaluations = 0;
  bool converged = true;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  virtual std::string method_label() const = 0;
  // This effect's term for one ray. `work` is this effect's counter, `shadow_work` the shadows'.
  // Must be thread-safe (called concurrently for different rays).
  virtual Rgb term(const PixelRay& ray, EffectWork& work, EffectWork& shadow_work) const = 0;
  // The same term by the effect's independent reference.
  virtual ReferenceValue reference(const PixelRay& ray) const = 0;
};

// Everything a factory may use. `shadowing` is never null (NoShadows when `shadows` is not named).
struct EffectContext {
  const Scene& scene;
  MethodSpec method;
  const nlohmann::json* settings;  // scene "settings"[name], or null
  const Shadowing* shadowing;
  bool absorption;  // attenuate the term along the viewing ray
  bool shadows;
};

struct MethodInfo {
  std::string name;
  std::vector<std::string> keys;  // accepted parameters
  std::string summary;
};

struct EffectInfo {
  std::string name;
  enum class Role { term, attenuation_term, modifier } role = Role::term;
  std::string summary;
  std::string default_method;
  std::vector<MethodInfo> methods;
  // Null for modifiers (shadows) and for reserved names whose implementation has not landed.
  std::function<std::unique_ptr<Effect>(const EffectContext&)> make;
};

// The built-in effects, then the registered ones, in the order the pipeline evaluates them
// (scene/effect_registry.cpp).
const std::vector<EffectInfo>& effect_registry();
// Adds an effect after the built-in ones, or replaces the effect of the same name (so registering
// twice is harmless). Call before scenes are read and pipelines built (not thread-safe; it may
// invalidate what effect_registry() and find_effect() returned before).
void register_effect(EffectInfo info);
const EffectInfo* find_effect(const std::string& name);  // null if unknown
// Throws std::invalid_argument when `spec` names no method of `effect` or an unknown parameter.
void check_effect_method(const EffectInfo& effect, const MethodSpec& spec);
// "name" or "name:key=value:...", checked with check_effect_method; throws std::invalid_argument.
MethodSpec parse_effect_method(const EffectInfo& effect, const std::string& text);
// One "EFFECT=METHOD" item (a command line's method choice) for an effect `scene` names: the effect
// and parse_effect_method's spec of METHOD. Throws EffectMethodError.
struct EffectMethodError : std::invalid_argument {
  enum class Kind {
    syntax,  // no '=', or nothing before it (effect empty)
    effect,  // not an effect the scene names
    method,  // parse_effect_method refused METHOD; what() is its message
  };
  EffectMethodError(Kind k, std::string name, const std::string& message)
      : std::invalid_argument(message), kind(k), effect(std::move(name)) {}
  Kind kind;
  std::string effect;
};
std::pair<std::string, MethodSpec> parse_effect_assignment(const Scene& scene,
                                                           const std::string& text);
// The n of a riemann:n=N method (default 128); std::invalid_argument "<label>: n must be an integer
// in [1, 1e8]".
int riemann_samples(const MethodSpec& spec);

}  // namespace rayint
