// Reading slab scenes; see slab_scene.hpp.
#include "rayint/input/slab_scene_reader.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

namespace {
using json = nlohmann::json;
using json_source::index_path;
using json_source::member_path;

std::vector<double> cosines(const JsonSchema& s, const json& j, const std::string& path) {
  s.non_empty_array(j, path, "cosines");
  std::vector<double> mu;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const double m = s.in_range(j[i], index_path(path, i), 0, 1);
    if (m <= 0) s.fail(index_path(path, i), "must be in (0, 1], got 0");
    mu.push_back(m);
  }
  return mu;
}
}  // namespace

SlabScene parse_slab_scene(const std::string& text, const std::string& source) {
  const JsonSchema s(source);
  const json j = json_source::parse(text, source);
  s.require_object(j, "");
  s.check_fields(j, "", {"name", "description", "medium", "phase", "lights", "detectors", "ground"});
  SlabScene scene;
  scene.name = s.non_empty_string(s.required(j, "", "name"), "name");
  if (const json* d = s.optional(j, "description")) scene.description = s.string_value(*d, "description");
  SlabProblem& p = scene.problem;

  const json& m = s.required(j, "", "medium");
  s.require_object(m, "medium");
  s.check_fields(m, "medium", {"type", "optical_thickness", "albedo"});
  const std::string type = s.string_value(s.required(m, "medium", "type"), "medium.type");
  if (type != "slab")
    s.fail("medium.type", "a slab scene needs \"slab\", got " + json_source::quoted(type) +
                              " (other media: rayint render)");
  p.tau = s.positive(s.required(m, "medium", "optical_thickness"), "medium.optical_thickness");
  p.albedo = s.in_range(s.required(m, "medium", "albedo"), "medium.albedo", 0, 1);

  const json& ph = s.required(j, "", "phase");
  s.require_object(ph, "phase");
  const std::string pt = s.string_value(s.required(ph, "phase", "type"), "phase.type");
  if (pt == "isotropic") {
    s.check_fields(ph, "phase", {"type"});
    p.phase = PhaseFunction::isotropic();
  } else if (pt == "henyey_greenstein") {
    s.check_fields(ph, "phase", {"type", "g"});
    p.phase = PhaseFunction::henyey_greenstein(s.in_range(s.required(ph, "phase", "g"), "phase.g", -1.0, 1.0, true));
  } else if (pt == "lambert_sphere") {
    s.check_fields(ph, "phase", {"type"});
    p.phase = PhaseFunction::lambert_sphere();
  } else if (pt == "legendre") {
    s.check_fields(ph, "phase", {"type", "coefficients"});
    const json& c = s.required(ph, "phase", "coefficients");
    s.non_empty_array(c, "phase.coefficients", "Legendre coefficients");
    for (std::size_t l = 0; l < c.size(); ++l) {
      const std::string at = index_path("phase.coefficients", l);
      const double chi = s.finite_number(c[l], at);
      if (l == 0 && chi != 1) s.fail(at, "must be 1 (the normalisation chi_0), got " + json_source::format_number(chi));
      if (l > 0 && !(std::fabs(chi) < 1)) s.fail(at, "must be in (-1, 1), got " + json_source::format_number(chi));
      scene.legendre.push_back(chi);
    }
    scene.phase_name = "legendre";
  } else if (pt == "tabulated") {
    s.check_fields(ph, "phase", {"type", "points"});
    const PiecewiseLinear t = s.points(s.required(ph, "phase", "points"), "phase.points");
    if (t.scalar.front() != -1 || t.scalar.back() != 1)
      s.fail("phase.points", "the cosines must run from -1 to 1");
    try {
      scene.legendre = legendre_from_table(t.scalar, t.value, kSlabTableOrder);
    } catch (const std::invalid_argument& e) {
      s.fail("phase.points", e.what());
    }
    scene.phase_name = "tabulated";
  } else {
    s.fail("phase.type", "must be isotropic, henyey_greenstein, lambert_sphere, legendre or tabulated, got " +
                             json_source::quoted(pt));
  }
  if (scene.phase_name.empty()) scene.phase_name = p.phase.name();

  const json& lights = s.required(j, "", "lights");
  s.non_empty_array(lights, "lights", "lights");
  if (lights.size() != 1) s.fail("lights", "a slab scene has exactly one light (beam or isotropic)");
  const std::string lp = index_path("lights", 0);
  const json& l = lights[0];
  s.require_object(l, lp);
  const std::string lt = s.string_value(s.required(l, lp, "type"), member_path(lp, "type"));
  if (lt == "beam") {
    s.check_fields(l, lp, {"type", "mu0"});
    p.source = SlabSource::beam;
    p.mu0 = s.in_range(s.required(l, lp, "mu0"), member_path(lp, "mu0"), 0, 1);
    if (p.mu0 <= 0) s.fail(member_path(lp, "mu0"), "must be in (0, 1], got 0");
  } else if (lt == "isotropic") {
    s.check_fields(l, lp, {"type"});
    p.source = SlabSource::isotropic;
  } else {
    s.fail(member_path(lp, "type"), "must be \"beam\" or \"isotropic\", got " + json_source::quoted(lt));
  }

  if (const json* g = s.optional(j, "ground")) {
    s.require_object(*g, "ground");
    s.check_fields(*g, "ground", {"type", "albedo"});
    const std::string gt = s.string_value(s.required(*g, "ground", "type"), "ground.type");
    if (gt != "lambertian") s.fail("ground.type", "must be \"lambertian\", got " + json_source::quoted(gt));
    p.ground_albedo = s.in_range(s.required(*g, "ground", "albedo"), "ground.albedo", 0, 1);
  }

  if (const json* d = s.optional(j, "detectors")) {
    s.require_object(*d, "detectors");
    s.check_fields(*d, "detectors", {"mu_up", "mu_down"});
    if (const json* u = s.optional(*d, "mu_up")) p.mu_up = cosines(s, *u, "detectors.mu_up");
    if (const json* w = s.optional(*d, "mu_down")) p.mu_down = cosines(s, *w, "detectors.mu_down");
  }
  validate(p);
  return scene;
}

SlabScene read_slab_scene(const std::string& path) {
  return parse_slab_scene(json_source::read_text_file(path), path);
}

}  // namespace rayint
