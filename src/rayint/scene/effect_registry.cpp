// The effects a scene may name, in the order the pipeline evaluates them: the built-in effects of
// scene/, then those registered with register_effect() (see scene/effect.hpp and docs/scenes.md).
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "rayint/scene/absorption_emission.hpp"
#include "rayint/scene/effect.hpp"
#include "rayint/scene/scattering_terms.hpp"

namespace rayint {

void EffectWork::add(const EffectWork& o) {
  seconds += o.seconds;
  cpu_seconds += o.cpu_seconds;
  setup_seconds += o.setup_seconds;
  setup_cpu_seconds += o.setup_cpu_seconds;
  rays += o.rays;
  samples += o.samples;
  shadow_rays += o.shadow_rays;
  shadow_samples += o.shadow_samples;
  lookups += o.lookups;
}

namespace {

std::vector<EffectInfo>& registry() {
  using Role = EffectInfo::Role;
  static std::vector<EffectInfo> effects = {
      {"absorption", Role::attenuation_term,
       "extinction along the viewing ray: the background seen through the medium, B*T; attenuates "
       "every other term",
       "exact on piecewise-linear media, else riemann:n=128",
       {{"exact", {}, "integrators/exact on the ray's linear segments"},
        {"riemann", {"n"}, "n midpoint samples"},
        {"nerf", {"n", "at"}, "NeRF quadrature: n intervals, one sample each at=mid|near"}},
       make_absorption_effect},
      {"emission", Role::term, "glow g = kappa*sigma_t along the viewing ray",
       "exact on piecewise-linear media, else riemann:n=128",
       {{"exact", {}, "integrators/exact (with absorption) or exact piece integrals (without)"},
        {"riemann", {"n"}, "n midpoint samples"},
        {"nerf", {"n", "at"}, "NeRF quadrature sum T_i alpha_i kappa_i: n intervals, one sample each at=mid|near"}},
       make_emission_effect},
      {"single_scattering", Role::term,
       "external light scattered once toward the eye: sigma_s * phase * E * T_light",
       "riemann:n=128", {{"riemann", {"n"}, "n midpoint samples"}}, make_single_scattering_effect},
      {"shadows", Role::modifier,
       "the light's optical depth to every scattering point (no term of its own)",
       "shadow_rays with the single-scattering n",
       {{"shadow_rays", {"n"}, "a shadow ray with n midpoint samples per lookup"},
        {"two_pass", {"grid"}, "Kajiya-Von Herzen light grid of grid^3 vertices, trilinear lookup"}},
       nullptr},
      {"shading", Role::term, "Max's gradient-strength surface shading (Lambert/Phong)",
       "riemann:n=128", {{"riemann", {"n"}, "n midpoint samples"}}, make_shading_effect},
      // Reserved: implemented in effects/ (scene does not link scattering) and put in this place
      // by register_standard_effects(). A program that links the library but never calls it
      // gets "not available in this build" naming the call, not "unknown effect".
      {"multiple_scattering", Role::term,
       "not registered: call rayint::register_standard_effects() (effects/standard_effects.hpp)",
       "", {}, nullptr},
  };
  return effects;
}

}  // namespace

const std::vector<EffectInfo>& effect_registry() { return registry(); }

void register_effect(EffectInfo info) {
  for (EffectInfo& e : registry())
    if (e.name == info.name) {
      e = std::move(info);
      return;
    }
  registry().push_back(std::move(info));
}

const EffectInfo* find_effect(const std::string& name) {
  for (const EffectInfo& e : effect_registry())
    if (e.name == name) return &e;
  return nullptr;
}

MethodSpec parse_effect_method(const EffectInfo& effect, const std::string& text) {
  MethodSpec spec;
  std::stringstream in(text);
  std::string part;
  std::getline(in, spec.name, ':');
  if (spec.name.empty()) throw std::invalid_argument("empty method name in '" + text + "'");
  while (std::getline(in, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
      throw std::invalid_argument("method " + spec.name + ": expected key=value, got '" + part + "'");
    if (spec.params.count(part.substr(0, eq)) != 0)
      throw std::invalid_argument("method " + spec.name + ": parameter " + part.substr(0, eq) + " given twice");
    spec.params[part.substr(0, eq)] = part.substr(eq + 1);
  }
  check_effect_method(effect, spec);
  return spec;
}

std::pair<std::string, MethodSpec> parse_effect_assignment(const Scene& scene,
                                                           const std::string& text) {
  using Kind = EffectMethodError::Kind;
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw EffectMethodError(Kind::syntax, "", "expected EFFECT=METHOD");
  std::string effect = text.substr(0, eq);
  const EffectInfo* info = find_effect(effect);
  if (info == nullptr || !scene.has(effect))
    throw EffectMethodError(Kind::effect, effect,
                            "effect " + effect + " is not named in " + scene.source);
  try {
    MethodSpec spec = parse_effect_method(*info, text.substr(eq + 1));
    return {std::move(effect), std::move(spec)};
  } catch (const std::invalid_argument& e) {
    throw EffectMethodError(Kind::method, effect, e.what());
  }
}

void check_effect_method(const EffectInfo& effect, const MethodSpec& spec) {
  std::string names;
  for (const MethodInfo& m : effect.methods) {
    names += (names.empty() ? "" : ", ") + m.name;
    if (m.name != spec.name) continue;
    for (const auto& kv : spec.params) {
      bool known = false;
      for (const std::string& k : m.keys) known = known || k == kv.first;
      if (!known) throw std::invalid_argument("method " + m.name + " has no parameter " + kv.first);
      if (kv.first == "at") {  // nerf's sample position: a word, not a count
        if (kv.second != "mid" && kv.second != "near")
          throw std::invalid_argument(m.name + ": at must be mid or near, not " + kv.second);
        continue;
      }
      const double v = spec.number(kv.first, 0.0);
      if (!(v >= 1 && v <= 1e8 && v == std::floor(v)))
        throw std::invalid_argument(m.name + ": " + kv.first + " must be an integer in [1, 1e8]");
    }
    return;
  }
  throw std::invalid_argument("unknown method " + spec.name + " for effect " + effect.name +
                              " (expected " + (names.empty() ? "none" : names) + ")");
}

int riemann_samples(const MethodSpec& spec) {
  const double n = spec.number("n", 128);
  if (!(n >= 1 && n <= 1e8 && n == std::floor(n)))
    throw std::invalid_argument(spec.label() + ": n must be an integer in [1, 1e8]");
  return static_cast<int>(n);
}

}  // namespace rayint
