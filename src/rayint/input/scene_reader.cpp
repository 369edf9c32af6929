#include "rayint/input/scene_reader.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "rayint/input/json_source.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/scene/cloud.hpp"
#include "rayint/scene/grid_field.hpp"
#include "rayint/scene/effect.hpp"

namespace rayint {

using json = nlohmann::json;
using json_source::index_path;
using json_source::member_path;

namespace {

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string resolve(const std::string& base_dir, const std::string& name) {
  if (!name.empty() && name[0] == '/') return name;
  return base_dir + "/" + name;
}

std::shared_ptr<const DensityField> parse_homogeneous(const json& j, const JsonSchema& s,
                                                      const std::string& path, const std::string&) {
  const std::string shape = s.non_empty_string(s.required(j, path, "shape"), member_path(path, "shape"));
  if (shape == "box") {
    s.check_fields(j, path, {"type", "shape", "density", "lower", "upper"});
    const double d = s.non_negative(s.required(j, path, "density"), member_path(path, "density"));
    const Vec3 lo = s.vec3(s.required(j, path, "lower"), member_path(path, "lower"));
    const Vec3 hi = s.vec3(s.required(j, path, "upper"), member_path(path, "upper"));
    for (int a = 0; a < 3; ++a)
      if (!(hi[a] > lo[a]))
        s.fail(index_path(member_path(path, "upper"), static_cast<std::size_t>(a)),
               "must be greater than lower[" + std::to_string(a) + "]");
    return std::make_shared<HomogeneousField>(d, Bounds{lo, hi}, false);
  }
  if (shape == "slab") {
    s.check_fields(j, path, {"type", "shape", "density", "z"});
    const double d = s.non_negative(s.required(j, path, "density"), member_path(path, "density"));
    const json& z = s.required(j, path, "z");
    s.array_of_size(z, member_path(path, "z"), 2, "[z_bottom, z_top]");
    const double z0 = s.finite_number(z[0], index_path(member_path(path, "z"), 0));
    const double z1 = s.finite_number(z[1], index_path(member_path(path, "z"), 1));
    if (!(z1 > z0)) s.fail(index_path(member_path(path, "z"), 1), "must be greater than z[0]");
    const double inf = std::numeric_limits<double>::infinity();
    return std::make_shared<HomogeneousField>(d, Bounds{Vec3(-inf, -inf, z0), Vec3(inf, inf, z1)}, true);
  }
  s.fail(member_path(path, "shape"), "must be \"box\" or \"slab\", got " + json_source::quoted(shape));
}

std::shared_ptr<const DensityField> parse_cloud(const json& j, const JsonSchema& s,
                                                const std::string& path, const std::string&) {
  s.check_fields(j, path, {"type", "preset", "seed", "ellipsoids", "scale", "threshold", "noise"});
  CloudParams c;
  const json* preset = s.optional(j, "preset");
  if (preset != nullptr) {
    const std::string p = s.non_empty_string(*preset, member_path(path, "preset"));
    if (p != "max1995") s.fail(member_path(path, "preset"), "unknown preset " + json_source::quoted(p) + " (expected max1995)");
    c = max_figure_cloud();
  }
  if (const json* seed = s.optional(j, "seed"))
    c.seed = static_cast<std::uint64_t>(s.integer(*seed, member_path(path, "seed"), 0, 9007199254740991LL));
  if (const json* e = s.optional(j, "ellipsoids")) {
    const std::string epath = member_path(path, "ellipsoids");
    s.non_empty_array(*e, epath, " of ellipsoids");
    c.ellipsoids.clear();
    for (std::size_t i = 0; i < e->size(); ++i) {
      const json& el = (*e)[i];
      const std::string p = index_path(epath, i);
      s.require_object(el, p);
      s.check_fields(el, p, {"center", "radii", "weight"});
      Ellipsoid ell;
      ell.center = s.vec3(s.required(el, p, "center"), member_path(p, "center"));
      ell.radii = s.vec3(s.required(el, p, "radii"), member_path(p, "radii"));
      for (int a = 0; a < 3; ++a)
        if (!(ell.radii[a] > 0.0))
          s.fail(index_path(member_path(p, "radii"), static_cast<std::size_t>(a)), "must be > 0");
      if (const json* w = s.optional(el, "weight")) ell.weight = s.non_negative(*w, member_path(p, "weight"));
      c.ellipsoids.push_back(ell);
    }
  } else if (preset == nullptr) {
    s.fail(member_path(path, "ellipsoids"), "missing required field (or give \"preset\": \"max1995\")");
  }
  if (const json* v = s.optional(j, "scale")) c.scale = s.non_negative(*v, member_path(path, "scale"));
  if (const json* v = s.optional(j, "threshold")) c.threshold = s.finite_number(*v, member_path(path, "threshold"));
  if (const json* n = s.optional(j, "noise")) {
    const std::string np = member_path(path, "noise");
    s.require_object(*n, np);
    s.check_fields(*n, np, {"amplitude", "frequency", "octaves", "lacunarity", "gain"});
    if (const json* v = s.optional(*n, "amplitude")) c.amplitude = s.non_negative(*v, member_path(np, "amplitude"));
    if (const json* v = s.optional(*n, "frequency")) c.frequency = s.positive(*v, member_path(np, "frequency"));
    if (const json* v = s.optional(*n, "octaves"))
      c.octaves = static_cast<int>(s.integer(*v, member_path(np, "octaves"), 0, 16));
    if (const json* v = s.optional(*n, "lacunarity")) c.lacunarity = s.in_range(*v, member_path(np, "lacunarity"), 1.0, 8.0);
    if (const json* v = s.optional(*n, "gain")) c.gain = s.in_range(*v, member_path(np, "gain"), 0.0, 1.0);
  }
  return std::make_shared<CloudField>(c);
}

// {"type": "grid", "grid": {grid object} | "grid_file": "x.json" | "x.vti" | "x.pvti" | "x.vtk"
//  [, "array": "name of the image's point array"]}, or
// {"type": "grid", "sample": {a medium object}, "dims": [nx, ny, nz]}: that medium sampled at the
// grid points (Max's cloud as a voxel volume).
std::shared_ptr<const DensityField> parse_grid(const json& j, const JsonSchema& s, const std::string& path,
                                               const std::string& base_dir) {
  s.check_fields(j, path, {"type", "grid", "grid_file", "array", "sample", "dims", "interpolation"});
  GridInterpolation interp = GridInterpolation::trilinear;
  if (const json* ip = s.optional(j, "interpolation")) {
    const std::string ipath = member_path(path, "interpolation");
    const std::string name = s.non_empty_string(*ip, ipath);
    if (name == "kuhn") interp = GridInterpolation::kuhn;
    else if (name != "trilinear") s.fail(ipath, "must be \"trilinear\" or \"kuhn\", got " + json_source::quoted(name));
  }
  const json* g = s.optional(j, "grid");
  const json* f = s.optional(j, "grid_file");
  const json* sm = s.optional(j, "sample");
  if ((g != nullptr) + (f != nullptr) + (sm != nullptr) != 1)
    s.fail(path, "give exactly one of grid, grid_file or sample");
  if (g != nullptr) return std::make_shared<GridField>(parse_voxel_grid(*g, s, member_path(path, "grid"), base_dir), interp);
  if (f != nullptr) {
    const std::string file = resolve(base_dir, s.non_empty_string(*f, member_path(path, "grid_file")));
    const json* a = s.optional(j, "array");
    return std::make_shared<GridField>(
        read_voxel_grid_file(file, a != nullptr ? s.non_empty_string(*a, member_path(path, "array")) : ""), interp);
  }
  if (s.optional(j, "array") != nullptr) s.fail(member_path(path, "array"), "only with \"grid_file\"");
  const json& dims = s.required(j, path, "dims");
  const std::string dpath = member_path(path, "dims");
  s.array_of_size(dims, dpath, 3, "[nx, ny, nz]");
  std::array<int, 3> d{};
  long long total = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    d[a] = static_cast<int>(s.integer(dims[a], index_path(dpath, a), 2, 4096));
    total *= d[a];
  }
  if (total > kMaxGridPoints) s.fail(dpath, "too many grid points (" + std::to_string(total) + ")");
  const std::string spath = member_path(path, "sample");
  s.require_object(*sm, spath);
  const std::string type = s.non_empty_string(s.required(*sm, spath, "type"), member_path(spath, "type"));
  std::shared_ptr<const DensityField> inner;
  for (const MediumType& t : medium_types())
    if (t.name == type && t.name != "grid") inner = t.parse(*sm, s, spath, base_dir);
  if (!inner) s.fail(member_path(spath, "type"), "must be a medium type other than grid, got " + json_source::quoted(type));
  if (!inner->bounds().finite()) s.fail(spath, "a sampled medium must be bounded (not a slab)");
  return std::make_shared<GridField>(sample_to_grid(*inner, d), interp);
}

std::array<PiecewiseLinear, kChannels> albedo_channels(const json& j, const JsonSchema& s, const std::string& path) {
  auto a = s.channels(j, path);
  for (int c = 0; c < kChannels; ++c)
    for (std::size_t i = 0; i < a[c].value.size(); ++i)
      if (a[c].value[i] > 1.0)
        s.fail(path, "albedo values must be in [0, 1], got " + json_source::format_number(a[c].value[i]));
  return a;
}

Rgb intensity(const json& j, const JsonSchema& s, const std::string& path) {
  if (j.is_number()) {
    const double v = s.non_negative(j, path);
    return {v, v, v};
  }
  return s.rgb(j, path);
}

}  // namespace

const std::vector<MediumType>& medium_types() {
  static const std::vector<MediumType> types = {
      {"homogeneous", parse_homogeneous},
      {"cloud", parse_cloud},
      {"grid", parse_grid},
  };
  return types;
}

Scene parse_scene(const json& root, const std::string& source, const std::string& base_dir) {
  const JsonSchema s(source);
  s.require_object(root, "");
  s.check_fields(root, "", {"name", "description", "medium", "transfer", "lights", "phase", "camera",
                            "rays", "background", "effects", "methods", "settings", "shading",
                            "reference"});
  Scene scene;
  scene.source = source;
  if (const json* v = s.optional(root, "name")) scene.name = s.string_value(*v, "name");
  if (const json* v = s.optional(root, "description")) scene.description = s.string_value(*v, "description");

  // effects first: other fields are required or refused depending on them
  const json& effects = s.required(root, "", "effects");
  s.non_empty_array(effects, "effects", " of effect names");
  for (std::size_t i = 0; i < effects.size(); ++i) {
    const std::string p = index_path("effects", i);
    const std::string name = s.non_empty_string(effects[i], p);
    const EffectInfo* info = find_effect(name);
    if (info == nullptr) {
      std::string names;
      for (const EffectInfo& e : effect_registry()) names += (names.empty() ? "" : ", ") + e.name;
      s.fail(p, "unknown effect " + json_source::quoted(name) + " (expected " + names + ")");
    }
    if (!info->make && info->role != EffectInfo::Role::modifier)
      s.fail(p, "effect " + name + " is not available in this build (" + info->summary + ")");
    if (scene.has(name)) s.fail(p, "effect " + name + " is named twice");
    scene.effects.push_back(name);
  }
  if (scene.has("shadows") && !scene.has("single_scattering") && !scene.has("shading"))
    s.fail("effects", "shadows needs single_scattering or shading (it shadows their light)");

  // medium
  const json& m = s.required(root, "", "medium");
  s.require_object(m, "medium");
  const std::string type = s.non_empty_string(s.required(m, "medium", "type"), "medium.type");
  std::shared_ptr<const DensityField> field;
  for (const MediumType& t : medium_types())
    if (t.name == type) field = t.parse(m, s, "medium", base_dir);
  if (!field) {
    std::string names;
    for (const MediumType& t : medium_types()) names += (names.empty() ? "" : ", ") + t.name;
    s.fail("medium.type", "unknown medium type " + json_source::quoted(type) + " (expected " + names + ")");
  }

  // transfer functions
  const json& tr = s.required(root, "", "transfer");
  s.require_object(tr, "transfer");
  s.check_fields(tr, "transfer", {"extinction", "albedo", "emission"});
  OpticalTransfer transfer;
  transfer.extinction = s.channels(s.required(tr, "transfer", "extinction"), "transfer.extinction");
  const PiecewiseLinear zero{{0.0}, {0.0}};
  transfer.albedo = {zero, zero, zero};
  transfer.emission = {zero, zero, zero};
  if (const json* a = s.optional(tr, "albedo")) transfer.albedo = albedo_channels(*a, s, "transfer.albedo");
  else if (scene.has("single_scattering")) s.fail("transfer.albedo", "missing (single_scattering needs an albedo)");
  if (const json* e = s.optional(tr, "emission")) transfer.emission = s.channels(*e, "transfer.emission");
  else if (scene.has("emission")) s.fail("transfer.emission", "missing (the emission effect needs it)");
  scene.medium = Medium(field, transfer);

  // lights
  if (const json* lights = s.optional(root, "lights")) {
    if (!lights->is_array()) s.fail("lights", "must be an array of lights");
    for (std::size_t i = 0; i < lights->size(); ++i) {
      const json& l = (*lights)[i];
      const std::string p = index_path("lights", i);
      s.require_object(l, p);
      const std::string lt = s.non_empty_string(s.required(l, p, "type"), member_path(p, "type"));
      Light light;
      if (lt == "directional") {
        s.check_fields(l, p, {"type", "direction", "intensity"});
        light.kind = Light::Kind::directional;
        light.direction = s.direction(s.required(l, p, "direction"), member_path(p, "direction"));
      } else if (lt == "point") {
        s.check_fields(l, p, {"type", "position", "intensity"});
        light.kind = Light::Kind::point;
        light.position = s.vec3(s.required(l, p, "position"), member_path(p, "position"));
      } else {
        s.fail(member_path(p, "type"), "must be \"directional\" or \"point\", got " + json_source::quoted(lt));
      }
      light.intensity = intensity(s.required(l, p, "intensity"), s, member_path(p, "intensity"));
      scene.lights.push_back(light);
    }
  }
  if ((scene.has("single_scattering") || scene.has("shading")) && scene.lights.empty())
    s.fail("lights", "single_scattering and shading need at least one light");

  // phase function
  if (const json* ph = s.optional(root, "phase")) {
    s.require_object(*ph, "phase");
    const std::string pt = s.non_empty_string(s.required(*ph, "phase", "type"), "phase.type");
    if (pt == "isotropic") {
      s.check_fields(*ph, "phase", {"type"});
      scene.phase = PhaseFunction::isotropic();
    } else if (pt == "henyey_greenstein") {
      s.check_fields(*ph, "phase", {"type", "g"});
      scene.phase = PhaseFunction::henyey_greenstein(s.in_range(s.required(*ph, "phase", "g"), "phase.g", -1.0, 1.0, true));
    } else if (pt == "lambert_sphere") {
      s.check_fields(*ph, "phase", {"type"});
      scene.phase = PhaseFunction::lambert_sphere();
    } else {
      s.fail("phase.type", "must be isotropic, henyey_greenstein or lambert_sphere, got " + json_source::quoted(pt));
    }
  }

  // camera or rays
  const json* cam = s.optional(root, "camera");
  const json* rays = s.optional(root, "rays");
  if ((cam != nullptr) == (rays != nullptr)) s.fail("", "give exactly one of camera or rays");
  if (cam != nullptr) scene.camera = s.camera(*cam, "camera");
  if (rays != nullptr) {
    s.non_empty_array(*rays, "rays", " of {origin, direction}");
    for (std::size_t i = 0; i < rays->size(); ++i) {
      const json& r = (*rays)[i];
      const std::string p = index_path("rays", i);
      s.require_object(r, p);
      s.check_fields(r, p, {"origin", "direction"});
      scene.rays.push_back({s.vec3(s.required(r, p, "origin"), member_path(p, "origin")),
                            s.direction(s.required(r, p, "direction"), member_path(p, "direction"))});
    }
  }

  // background
  if (const json* bg = s.optional(root, "background")) {
    s.require_object(*bg, "background");
    s.check_fields(*bg, "background", {"color", "image"});
    if (const json* c = s.optional(*bg, "color")) scene.background.color = s.rgb(*c, "background.color");
    if (const json* im = s.optional(*bg, "image")) {
      const std::string file = resolve(base_dir, s.non_empty_string(*im, "background.image"));
      try {
        scene.background.image = std::make_shared<Image>(read_png(file));
      } catch (const std::exception& e) {
        s.fail("background.image", json_source::one_line(e.what()));
      }
    }
  }

  // methods per effect
  if (const json* methods = s.optional(root, "methods")) {
    s.require_object(*methods, "methods");
    for (const auto& item : methods->items()) {
      const std::string p = member_path("methods", item.key());
      if (!scene.has(item.key())) s.fail(p, "effect " + item.key() + " is not named in effects");
      const std::string text = s.non_empty_string(item.value(), p);
      try {
        const MethodSpec spec = parse_effect_method(*find_effect(item.key()), text);
        if (spec.name == "exact" && !exact_along_rays(*field))
          throw std::invalid_argument("method exact needs a medium that is piecewise linear along rays "
                                      "(homogeneous or grid), not " + field->kind());
        if (spec.name == "two_pass" && !field->bounds().finite())
          throw std::invalid_argument("two_pass needs a bounded medium (not a slab)");
        if (spec.name == "two_pass" && spec.number("grid", 64) < 2)
          throw std::invalid_argument("two_pass: grid must be >= 2");
        scene.methods[item.key()] = spec;
      } catch (const std::invalid_argument& e) {
        s.fail(p, json_source::one_line(e.what()));
      }
    }
  }
  if (const json* settings = s.optional(root, "settings")) {
    s.require_object(*settings, "settings");
    for (const auto& item : settings->items()) {
      if (!scene.has(item.key()))
        s.fail(member_path("settings", item.key()), "effect " + item.key() + " is not named in effects");
      s.require_object(item.value(), member_path("settings", item.key()));
      scene.settings[item.key()] = item.value();
    }
  }

  if (const json* sh = s.optional(root, "shading")) {
    s.require_object(*sh, "shading");
    s.check_fields(*sh, "shading", {"diffuse", "specular", "shininess", "strength"});
    if (const json* v = s.optional(*sh, "diffuse")) scene.shading.diffuse = s.rgb(*v, "shading.diffuse");
    if (const json* v = s.optional(*sh, "specular")) scene.shading.specular = s.rgb(*v, "shading.specular");
    if (const json* v = s.optional(*sh, "shininess")) scene.shading.shininess = s.in_range(*v, "shading.shininess", 0.0, 1e4);
    if (const json* v = s.optional(*sh, "strength")) scene.shading.strength = s.non_negative(*v, "shading.strength");
  }
  if (const json* ref = s.optional(root, "reference")) {
    s.require_object(*ref, "reference");
    s.check_fields(*ref, "reference", {"rtol", "max_intervals"});
    if (const json* v = s.optional(*ref, "rtol")) scene.reference.rtol = s.in_range(*v, "reference.rtol", 1e-14, 1e-3);
    if (const json* v = s.optional(*ref, "max_intervals"))
      scene.reference.max_intervals = static_cast<int>(s.integer(*v, "reference.max_intervals", 1, 10000000));
  }
  return scene;
}

Scene parse_scene_text(std::string_view text, const std::string& source, const std::string& base_dir) {
  return parse_scene(json_source::parse(text, source), source, base_dir);
}

Scene read_scene_file(const std::string& path) {
  return parse_scene_text(json_source::read_text_file(path), path, dir_of(path));
}

}  // namespace rayint
