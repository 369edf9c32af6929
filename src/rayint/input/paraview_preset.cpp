// Reading ParaView colour-map presets (format in the header) and importing them as rayint
// transfer functions. Parsing goes through json_source::parse (duplicate keys, overflowing
// numbers and syntax errors reported at their field or line) and the JsonSchema walk.
//
// What is checked, with the reason:
//  - RGBPoints and Points are flat lists of 4-tuples with at least one tuple; x strictly
//    increasing (VTK would silently drop all but one of equal x values, which changes the curve);
//  - every number finite; colours and opacities >= 0 (rayint's kappa and rho are >= 0);
//    midpoint and sharpness in [0, 1] (vtkPiecewiseFunction::AddPoint refuses others);
//  - ColorSpace one of RGB, HSV, Lab, Diverging. "Step" and "Lab/CIEDE2000" are refused as not
//    implemented; "CIELAB" (one ParaView preset uses it) is not one of ParaView's colour-space
//    names, so what ParaView does with it is not VTK's Lab: refused, naming the field;
//  - under the per-sample convention, every opacity < 1 (-ln(1 - alpha)/d is infinite at 1).
// Other fields (NanColor, Creator, License, DefaultMap, ...) do not shape the curves; their names
// are returned so that the import report can list them.
#include "rayint/input/paraview_preset.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {
namespace {

using nlohmann::json;
using json_source::format_number;
using json_source::index_path;
using json_source::member_path;

// The 4-tuples of a flat list: at least one, count a multiple of 4, every entry finite.
std::vector<std::array<double, 4>> tuples(const JsonSchema& s, const json& j, const std::string& path,
                                          const char* layout) {
  if (!j.is_array() || j.empty() || j.size() % 4 != 0)
    s.fail(path, std::string("must be a flat list of ") + layout + " tuples (a multiple of 4 numbers), got " +
                     (j.is_array() ? std::to_string(j.size()) + " numbers" : std::string(j.type_name())));
  std::vector<std::array<double, 4>> out(j.size() / 4);
  for (std::size_t i = 0; i < j.size(); ++i) out[i / 4][i % 4] = s.finite_number(j[i], index_path(path, i));
  for (std::size_t k = 1; k < out.size(); ++k)
    if (!(out[k][0] > out[k - 1][0]))
      s.fail(index_path(path, 4 * k), "scalars must be strictly increasing (" + format_number(out[k][0]) +
                                          " after " + format_number(out[k - 1][0]) + ")");
  if (!std::isfinite(out.back()[0] - out.front()[0]))
    s.fail(path, "the scalars span more than the largest double");
  return out;
}

void require_non_negative(const JsonSchema& s, double v, const std::string& path) {
  if (!(v >= 0.0)) s.fail(path, "must be >= 0, got " + format_number(v));
}
void require_unit(const JsonSchema& s, double v, const std::string& path) {
  if (!(v >= 0.0 && v <= 1.0)) s.fail(path, "must be in [0, 1] (as VTK requires), got " + format_number(v));
}

ParaViewPreset read_preset(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  ParaViewPreset p;
  p.source = s.source();
  p.field = path;
  p.name = s.string_value(s.required(j, path, "Name"), member_path(path, "Name"));
  const std::string cs_path = member_path(path, "ColorSpace");
  p.color_space = s.string_value(s.required(j, path, "ColorSpace"), cs_path);
  if (p.color_space == "RGB") p.color.space = VtkColorSpace::rgb;
  else if (p.color_space == "HSV") p.color.space = VtkColorSpace::hsv;
  else if (p.color_space == "Lab") p.color.space = VtkColorSpace::lab;
  else if (p.color_space == "Diverging") p.color.space = VtkColorSpace::diverging;
  else if (p.color_space == "Step" || p.color_space == "Lab/CIEDE2000")
    s.fail(cs_path, "\"" + p.color_space + "\" is not supported (RGB, HSV, Lab, Diverging are)");
  else
    s.fail(cs_path, "unknown colour space " + json_source::quoted(p.color_space) +
                        " (ParaView's are RGB, HSV, Lab, Diverging, Step, Lab/CIEDE2000)");
  if (const json* w = s.optional(j, "HSVWrap")) {
    const std::string wpath = member_path(path, "HSVWrap");
    if (w->is_boolean()) p.color.hsv_wrap = w->get<bool>();
    else p.color.hsv_wrap = s.integer(*w, wpath, 0, 1) == 1;
  }
  const std::string rgb_path = member_path(path, "RGBPoints");
  if (s.optional(j, "RGBPoints") == nullptr && s.optional(j, "IndexedColors") != nullptr)
    s.fail(rgb_path, "missing: a categorical preset (IndexedColors only) has no continuous colour map");
  for (const auto& t : tuples(s, s.required(j, path, "RGBPoints"), rgb_path, "[x, r, g, b]")) {
    const std::size_t k = p.color.nodes.size();
    for (int c = 1; c <= 3; ++c) require_non_negative(s, t[c], index_path(rgb_path, 4 * k + c));
    p.color.nodes.push_back({t[0], {t[1], t[2], t[3]}, 0.5, 0.0});
  }
  if (const json* pts = s.optional(j, "Points")) {
    const std::string ppath = member_path(path, "Points");
    VtkPiecewiseFunction f;
    for (const auto& t : tuples(s, *pts, ppath, "[x, opacity, midpoint, sharpness]")) {
      const std::size_t k = f.nodes.size();
      require_non_negative(s, t[1], index_path(ppath, 4 * k + 1));
      require_unit(s, t[2], index_path(ppath, 4 * k + 2));
      require_unit(s, t[3], index_path(ppath, 4 * k + 3));
      f.nodes.push_back({t[0], t[1], t[2], t[3]});
    }
    p.opacity = std::move(f);
  }
  for (const auto& item : j.items())
    if (item.key() != "Name" && item.key() != "ColorSpace" && item.key() != "RGBPoints" &&
        item.key() != "Points" && item.key() != "HSVWrap")
      p.ignored_fields.push_back(item.key());
  return p;
}

// A scalar mapped from [a0, a1] to [b0, b1], the ends exactly.
double rescale(double x, double a0, double a1, double b0, double b1) {
  if (x == a0) return b0;
  if (x == a1) return b1;
  return b0 + (x - a0) * ((b1 - b0) / (a1 - a0));
}

}  // namespace

std::optional<OpacityConvention> parse_convention(const std::string& name) {
  std::string n = name;
  for (char& c : n)
    if (c == '-') c = '_';
  for (OpacityConvention c : {OpacityConvention::density, OpacityConvention::unit_distance,
                              OpacityConvention::sample_distance, OpacityConvention::nerf_sigma})
    if (n == convention_name(c)) return c;
  return std::nullopt;
}

ParaViewPreset parse_paraview_preset(std::string_view text, const std::string& source,
                                     const std::string& name) {
  const json root = json_source::parse(text, source);
  const JsonSchema s(source);
  if (root.is_object()) {
    ParaViewPreset p = read_preset(s, root, "");
    if (!name.empty() && p.name != name)
      s.fail("Name", "the preset is " + json_source::quoted(p.name) + ", not " + json_source::quoted(name));
    return p;
  }
  s.non_empty_array(root, "", " of presets");
  if (name.empty() && root.size() > 1)
    s.fail("", "holds " + std::to_string(root.size()) + " presets: name one (--name)");
  for (std::size_t i = 0; i < root.size(); ++i) {
    const std::string path = index_path("", i);
    s.require_object(root[i], path);
    const std::string n = s.string_value(s.required(root[i], path, "Name"), member_path(path, "Name"));
    if (name.empty() || n == name) return read_preset(s, root[i], path);
  }
  s.fail("", "no preset named " + json_source::quoted(name) + " among " + std::to_string(root.size()));
}

ParaViewPreset read_paraview_preset_file(const std::string& path, const std::string& name) {
  return parse_paraview_preset(json_source::read_text_file(path), path, name);
}

PresetImport import_paraview_preset_text(std::string_view text, const PresetImportRequest& r) {
  PresetImport out;
  out.preset = parse_paraview_preset(text, r.file, r.name);
  ParaViewPreset& p = out.preset;
  const JsonSchema s(p.source);
  if (!(r.options.distance > 0.0 && std::isfinite(r.options.distance)))
    field::fail(r.request_source, r.distance_field, "must be finite and > 0, got " + format_number(r.options.distance));
  // Below ~1e-12 the bisection would chase the rounding of the curves' own evaluation (~1e-15).
  if (!(r.options.tolerance >= 1e-12 && r.options.tolerance < 1.0))
    field::fail(r.request_source, r.tolerance_field, "must be in [1e-12, 1), got " + format_number(r.options.tolerance));
  VtkPiecewiseFunction opacity;
  if (r.constant_opacity) {
    const double a = *r.constant_opacity;
    if (!(std::isfinite(a) && a >= 0.0))
      field::fail(r.request_source, r.opacity_field, "must be finite and >= 0, got " + format_number(a));
    if (r.options.convention == OpacityConvention::sample_distance && !(a < 1.0))
      field::fail(r.request_source, r.opacity_field,
                  "opacity " + format_number(a) + " per sample is fully opaque: -ln(1 - alpha)/d is infinite; "
                  "use an opacity < 1 or the unit-distance convention");
    opacity.nodes.push_back({p.color.nodes.front().x, a, 0.5, 0.0});
  } else if (p.opacity) {
    opacity = *p.opacity;
    if (r.options.convention == OpacityConvention::sample_distance)
      for (std::size_t k = 0; k < opacity.nodes.size(); ++k)
        if (!(opacity.nodes[k].y < 1.0))
          s.fail(index_path(member_path(p.field, "Points"), 4 * k + 1),
                 "opacity " + format_number(opacity.nodes[k].y) +
                     " per sample is fully opaque: density -ln(1 - alpha)/d is infinite; "
                     "use opacities < 1 or the unit-distance convention");
  } else {
    s.fail(member_path(p.field, "Points"),
           "missing: the preset has no opacity Points; give a constant opacity (--opacity)");
  }
  if (r.range) {
    const double b0 = (*r.range)[0], b1 = (*r.range)[1];
    if (!(std::isfinite(b0) && std::isfinite(b1) && b1 > b0 && std::isfinite(b1 - b0)))
      field::fail(r.request_source, r.range_field, "must be two finite numbers lo < hi, got [" +
                                                 format_number(b0) + ", " + format_number(b1) + "]");
    const double a0 = p.color.nodes.front().x, a1 = p.color.nodes.back().x;
    if (!(a1 > a0)) s.fail(member_path(p.field, "RGBPoints"), "a single colour point has no range to rescale");
    for (auto& n : p.color.nodes) n.x = rescale(n.x, a0, a1, b0, b1);
    for (auto& n : opacity.nodes) n.x = rescale(n.x, a0, a1, b0, b1);
    for (std::size_t k = 1; k < opacity.nodes.size(); ++k)
      if (!(opacity.nodes[k].x > opacity.nodes[k - 1].x))
        s.fail(member_path(p.field, "Points"), "scalars not strictly increasing after rescaling to the range");
    for (std::size_t k = 1; k < p.color.nodes.size(); ++k)
      if (!(p.color.nodes[k].x > p.color.nodes[k - 1].x))
        s.fail(member_path(p.field, "RGBPoints"), "scalars not strictly increasing after rescaling to the range");
    if (p.opacity) p.opacity = opacity;
  }
  try {
    out.result = import_vtk_transfer_function(p.color, opacity, r.options);
  } catch (const std::length_error& e) {
    field::fail(r.request_source, r.tolerance_field, std::string(e.what()) + "; give a larger tolerance");
  }
  // Extreme but finite inputs can overflow VTK's formulas (Hermite slopes, colour conversions).
  auto finite = [](const std::array<PiecewiseLinear, kChannels>& f) {
    for (const PiecewiseLinear& c : f)
      for (std::size_t k = 0; k < c.scalar.size(); ++k)
        if (!std::isfinite(c.scalar[k]) || !std::isfinite(c.value[k]) || c.value[k] < 0.0) return false;
    return true;
  };
  if (!finite(out.result.transfer.density))
    s.fail(member_path(p.field, r.constant_opacity ? "RGBPoints" : "Points"),
           "the imported density is not finite (values too large for the convention's formula)");
  if (!finite(out.result.transfer.color))
    s.fail(member_path(p.field, "RGBPoints"), "the imported colour is not finite (values too large)");
  return out;
}

PresetImport import_paraview_preset(const PresetImportRequest& r) {
  return import_paraview_preset_text(json_source::read_text_file(r.file), r);
}

}  // namespace rayint
