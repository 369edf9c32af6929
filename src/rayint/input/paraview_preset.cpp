// Reading ParaView colour-map presets (format in the header) and importing them as rayint
// transfer functions. Parsing goes through json_source::parse (duplicate keys, overflowing
// numbers and syntax errors reported at their field or line) and the JsonSchema walk.
//
// What is checked, with the reason:
//  - RGBPoints and Points are flat lists of 4-tuples with at least one tuple. RGBPoints' x
//    non-decreasing: ParaView turns AllowDuplicateScalars on, so a repeated x is a jump (two or
//    more nodes at one x); Points' x strictly increasing (a decreasing x would be re-sorted by VTK:
//    refused rather than guessed);
//  - every number finite; colours in [0, 1] (VTK does not clamp stored colours: its RGB
//    interpolation returns them as given, its Lab/HSV conversions assume [0, 1], and what a
//    renderer's byte lookup table makes of 1.2 is its own; none of ParaView's presets has one);
//    opacities >= 0 (rayint's rho is >= 0); midpoint and sharpness in [0, 1]
//    (vtkPiecewiseFunction::AddPoint refuses others);
//  - IndexedColors (a categorical map: ParaView's IndexedLookup) refused: no continuous function;
//  - ColorSpace one of RGB, HSV, Lab, Diverging, Step; "CIELAB" read as RGB (ParaView 5.11 applies
//    it so: measured, scripts/paraview-presets.py); "Lab/CIEDE2000" refused as not implemented;
//  - UseLogScale needs the first scalar > 0 (VTK otherwise silently uses the linear scale);
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
                                          const char* layout, bool repeats_allowed) {
  if (!j.is_array() || j.empty() || j.size() % 4 != 0)
    s.fail(path, std::string("must be a flat list of ") + layout + " tuples (a multiple of 4 numbers), got " +
                     (j.is_array() ? std::to_string(j.size()) + " numbers" : std::string(j.type_name())));
  std::vector<std::array<double, 4>> out(j.size() / 4);
  for (std::size_t i = 0; i < j.size(); ++i) out[i / 4][i % 4] = s.finite_number(j[i], index_path(path, i));
  for (std::size_t k = 1; k < out.size(); ++k)
    if (repeats_allowed ? !(out[k][0] >= out[k - 1][0]) : !(out[k][0] > out[k - 1][0]))
      s.fail(index_path(path, 4 * k), std::string("scalars must be ") +
                                          (repeats_allowed ? "non-decreasing (" : "strictly increasing (") +
                                          format_number(out[k][0]) + " after " + format_number(out[k - 1][0]) + ")");
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
void require_colour(const JsonSchema& s, double v, const std::string& path) {
  if (!(v >= 0.0 && v <= 1.0))
    s.fail(path, "colour components must be in [0, 1] (VTK's colour spaces assume it and do not clamp), got " +
                     format_number(v));
}
bool flag(const JsonSchema& s, const json& j, const std::string& path) {
  return j.is_boolean() ? j.get<bool>() : s.integer(j, path, 0, 1) == 1;
}

ParaViewPreset read_preset(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  ParaViewPreset p;
  p.source = s.source();
  p.field = path;
  p.name = s.string_value(s.required(j, path, "Name"), member_path(path, "Name"));
  // ParaView applies a preset with IndexedColors as a categorical lookup (IndexedLookup 1),
  // whatever else it holds.
  if (s.optional(j, "IndexedColors") != nullptr)
    s.fail(member_path(path, "IndexedColors"),
           "a categorical colour map (IndexedColors): categorical maps have no continuous transfer function");
  const std::string cs_path = member_path(path, "ColorSpace");
  p.color_space = s.string_value(s.required(j, path, "ColorSpace"), cs_path);
  if (p.color_space == "RGB") p.color.space = VtkColorSpace::rgb;
  else if (p.color_space == "HSV") p.color.space = VtkColorSpace::hsv;
  else if (p.color_space == "Lab") p.color.space = VtkColorSpace::lab;
  else if (p.color_space == "Diverging") p.color.space = VtkColorSpace::diverging;
  else if (p.color_space == "Step") p.color.space = VtkColorSpace::step;
  else if (p.color_space == "CIELAB") {
    p.color.space = VtkColorSpace::rgb;
    p.notes.push_back(cs_path + ": \"CIELAB\" is not a ParaView colour space; ParaView 5.11 applies this preset "
                      "as RGB, and so does rayint");
  } else if (p.color_space == "Lab/CIEDE2000")
    s.fail(cs_path, "\"" + p.color_space + "\" is not supported (RGB, HSV, Lab, Diverging, Step are)");
  else
    s.fail(cs_path, "unknown colour space " + json_source::quoted(p.color_space) +
                        " (ParaView's are RGB, HSV, Lab, Diverging, Step, Lab/CIEDE2000)");
  if (const json* w = s.optional(j, "HSVWrap")) p.color.hsv_wrap = flag(s, *w, member_path(path, "HSVWrap"));
  const std::string rgb_path = member_path(path, "RGBPoints");
  for (const auto& t : tuples(s, s.required(j, path, "RGBPoints"), rgb_path, "[x, r, g, b]", true)) {
    const std::size_t k = p.color.nodes.size();
    for (int c = 1; c <= 3; ++c) require_colour(s, t[c], index_path(rgb_path, 4 * k + c));
    p.color.nodes.push_back({t[0], {t[1], t[2], t[3]}, 0.5, 0.0});
  }
  if (const json* l = s.optional(j, "UseLogScale")) {
    const std::string lpath = member_path(path, "UseLogScale");
    p.color.log_scale = flag(s, *l, lpath);
    if (p.color.log_scale && !(p.color.nodes.front().x > 0.0))
      s.fail(lpath, "a log scale needs scalars > 0, and the first RGBPoints scalar is " +
                        format_number(p.color.nodes.front().x) + " (VTK would silently use the linear scale)");
  }
  if (const json* pts = s.optional(j, "Points")) {
    const std::string ppath = member_path(path, "Points");
    VtkPiecewiseFunction f;
    for (const auto& t : tuples(s, *pts, ppath, "[x, opacity, midpoint, sharpness]", false)) {
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
        item.key() != "Points" && item.key() != "HSVWrap" && item.key() != "UseLogScale")
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
                                     const PresetSelection& which) {
  const json root = json_source::parse(text, source);
  const JsonSchema s(source);
  const std::string& name = which.name;
  const std::string& index_source = which.request_source.empty() ? source : which.request_source;
  if (root.is_object()) {
    if (which.index && *which.index != 0)
      field::fail(index_source, which.index_field, source + " holds one preset (index 0), not a list");
    ParaViewPreset p = read_preset(s, root, "");
    if (!name.empty() && p.name != name)
      s.fail("Name", "the preset is " + json_source::quoted(p.name) + ", not " + json_source::quoted(name));
    return p;
  }
  s.non_empty_array(root, "", " of presets");
  if (which.index) {
    if (*which.index >= root.size())
      field::fail(index_source, which.index_field, "no preset [" + std::to_string(*which.index) + "]: " + source +
                                                       " holds " + std::to_string(root.size()));
    const std::string path = index_path("", *which.index);
    s.require_object(root[*which.index], path);
    const std::string n = s.string_value(s.required(root[*which.index], path, "Name"), member_path(path, "Name"));
    if (!name.empty() && n != name)
      s.fail(member_path(path, "Name"), "the preset is " + json_source::quoted(n) + ", not " + json_source::quoted(name));
    return read_preset(s, root[*which.index], path);
  }
  if (name.empty() && root.size() > 1)
    s.fail("", "holds " + std::to_string(root.size()) + " presets: name one (--name)");
  std::vector<std::size_t> matches;
  for (std::size_t i = 0; i < root.size(); ++i) {
    const std::string path = index_path("", i);
    s.require_object(root[i], path);
    const std::string n = s.string_value(s.required(root[i], path, "Name"), member_path(path, "Name"));
    if (name.empty() || n == name) matches.push_back(i);
  }
  if (matches.empty())
    s.fail("", "no preset named " + json_source::quoted(name) + " among " + std::to_string(root.size()));
  if (matches.size() > 1) {
    std::string list;
    for (std::size_t i : matches) {
      const json* cs = s.optional(root[i], "ColorSpace");
      list += (list.empty() ? "" : ", ") + index_path("", i) + " (" +
              (s.optional(root[i], "IndexedColors") ? std::string("categorical")
               : cs && cs->is_string()               ? cs->get<std::string>()
                                                     : std::string("no ColorSpace")) +
              ")";
    }
    s.fail("", std::to_string(matches.size()) + " presets are named " + json_source::quoted(name) + ": " + list +
                   "; choose one by its index (" + which.index_field + ")");
  }
  return read_preset(s, root[matches.front()], index_path("", matches.front()));
}

ParaViewPreset parse_paraview_preset(std::string_view text, const std::string& source,
                                     const std::string& name) {
  PresetSelection which;
  which.name = name;
  return parse_paraview_preset(text, source, which);
}

ParaViewPreset read_paraview_preset_file(const std::string& path, const std::string& name) {
  return parse_paraview_preset(json_source::read_text_file(path), path, name);
}

PresetImport import_paraview_preset_text(std::string_view text, const PresetImportRequest& r) {
  PresetImport out;
  out.preset = parse_paraview_preset(text, r.file, PresetSelection{r.name, r.index, r.request_source, r.index_field});
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
    // ParaView's default opacity for a new colour map (its PiecewiseFunction proxy's Points, as
    // exported in tests/data/tf/paraview-5.11-exported.json): 0 at the first scalar, 1 at the last.
    out.default_opacity = true;
    const double x0 = p.color.nodes.front().x, x1 = p.color.nodes.back().x;
    if (r.options.convention == OpacityConvention::sample_distance)
      s.fail(member_path(p.field, "Points"),
             "missing, and the default opacity (ParaView's ramp 0 -> 1) reaches 1, fully opaque per sample; "
             "add opacity Points < 1 or give a constant (" + r.opacity_field + ")");
    if (x1 > x0) {
      opacity.nodes.push_back({x0, 0.0, 0.5, 0.0});
      opacity.nodes.push_back({x1, 1.0, 0.5, 0.0});
    } else {
      opacity.nodes.push_back({x0, 1.0, 0.5, 0.0});
    }
  }
  if (r.range) {
    const double b0 = (*r.range)[0], b1 = (*r.range)[1];
    if (!(std::isfinite(b0) && std::isfinite(b1) && b1 > b0 && std::isfinite(b1 - b0)))
      field::fail(r.request_source, r.range_field, "must be two finite numbers lo < hi, got [" +
                                                 format_number(b0) + ", " + format_number(b1) + "]");
    const double a0 = p.color.nodes.front().x, a1 = p.color.nodes.back().x;
    if (!(a1 > a0)) s.fail(member_path(p.field, "RGBPoints"), "a single colour point has no range to rescale");
    std::vector<double> before;
    for (const auto& n : p.color.nodes) before.push_back(n.x);
    if (p.color.log_scale) {
      // As ParaView rescales a log-scale map to a log-scale lookup table (vtkNormalize and
      // vtkRescaleNormalizedControlPoints in log space): log10 x mapped linearly. The opacity
      // function is not on the log scale (ParaView 5.11's is linear: paraview-5.11-oracle.json).
      if (!(b0 > 0.0))
        field::fail(r.request_source, r.range_field, "a log-scale colour map needs a range > 0, got [" +
                                                         format_number(b0) + ", " + format_number(b1) + "]");
      const double l0 = std::log10(a0), l1 = std::log10(a1), m0 = std::log10(b0), m1 = std::log10(b1);
      for (auto& n : p.color.nodes)
        n.x = n.x == a0 ? b0 : n.x == a1 ? b1 : std::pow(10.0, rescale(std::log10(n.x), l0, l1, m0, m1));
    } else {
      for (auto& n : p.color.nodes) n.x = rescale(n.x, a0, a1, b0, b1);
    }
    for (auto& n : opacity.nodes) n.x = rescale(n.x, a0, a1, b0, b1);
    for (std::size_t k = 1; k < opacity.nodes.size(); ++k)
      if (!(opacity.nodes[k].x > opacity.nodes[k - 1].x))
        s.fail(member_path(p.field, "Points"), "scalars not strictly increasing after rescaling to the range");
    // Repeated scalars stay repeated (the same input gives the same output); distinct ones must stay distinct.
    for (std::size_t k = 1; k < p.color.nodes.size(); ++k)
      if (before[k] > before[k - 1] && !(p.color.nodes[k].x > p.color.nodes[k - 1].x))
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
