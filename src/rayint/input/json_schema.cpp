#include "rayint/input/json_schema.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "rayint/input/json_source.hpp"
#include "rayint/input/paraview_preset.hpp"

namespace rayint {

using json_source::format_number;
using json_source::index_path;
using json_source::member_path;

namespace {
template <class Names>
std::string join(const Names& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

template <class Json>
std::string type_of(const Json& j) { return j.type_name(); }

// Every key of `object` must be one of `allowed` (the first that is not is reported).
template <class Json, class Names>
void check_keys(const BasicJsonSchema<Json>& s, const Json& object, const std::string& path,
                const Names& allowed) {
  for (const auto& item : object.items()) {
    bool known = false;
    for (const auto& a : allowed) known = known || item.key() == a;
    if (!known)
      s.fail(member_path(path, item.key()), "unknown field (expected " + join(allowed) + ")");
  }
}
}  // namespace

template <class Json>
void BasicJsonSchema<Json>::fail(const std::string& path, const std::string& what) const {
  json_source::fail(source_, path, what);
}

template <class Json>
void BasicJsonSchema<Json>::require_object(const json& j, const std::string& path) const {
  if (!j.is_object()) fail(path, "must be an object, got " + type_of(j));
}

template <class Json>
void BasicJsonSchema<Json>::check_fields(const json& object, const std::string& path,
                                         std::initializer_list<const char*> allowed) const {
  check_keys(*this, object, path, allowed);
}

template <class Json>
void BasicJsonSchema<Json>::check_fields(const json& object, const std::string& path,
                                         const std::vector<std::string>& allowed) const {
  check_keys(*this, object, path, allowed);
}

template <class Json>
const Json& BasicJsonSchema<Json>::required(const json& object, const std::string& path,
                                           const char* key) const {
  const auto it = object.find(key);
  if (it == object.end()) fail(member_path(path, key), "missing required field");
  return *it;
}

template <class Json>
const Json* BasicJsonSchema<Json>::optional(const json& object, const char* key) const {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

template <class Json>
std::string BasicJsonSchema<Json>::non_empty_string(const json& j, const std::string& path) const {
  if (!j.is_string() || j.template get_ref<const std::string&>().empty())
    fail(path, "must be a non-empty string, got " +
                   (j.is_string() ? std::string("\"\"") : type_of(j)));
  return j.template get<std::string>();
}

template <class Json>
std::string BasicJsonSchema<Json>::string_value(const json& j, const std::string& path) const {
  if (!j.is_string()) fail(path, "must be a string, got " + type_of(j));
  return j.template get<std::string>();
}

template <class Json>
bool BasicJsonSchema<Json>::boolean(const json& j, const std::string& path) const {
  if (!j.is_boolean()) fail(path, "must be true or false, got " + type_of(j));
  return j.template get<bool>();
}

template <class Json>
double BasicJsonSchema<Json>::finite_number(const json& j, const std::string& path) const {
  if (!j.is_number()) fail(path, "must be a number, got " + type_of(j));
  const double x = j.template get<double>();
  if (!std::isfinite(x)) fail(path, "must be finite, got " + format_number(x));
  return x;
}

template <class Json>
double BasicJsonSchema<Json>::non_negative(const json& j, const std::string& path) const {
  if (!j.is_number()) fail(path, "must be a number, got " + type_of(j));
  const double x = j.template get<double>();
  if (!(std::isfinite(x) && x >= 0.0))
    fail(path, "must be finite and >= 0, got " + format_number(x));
  return x + 0.0;  // -0 becomes +0
}

template <class Json>
double BasicJsonSchema<Json>::positive(const json& j, const std::string& path) const {
  if (!j.is_number()) fail(path, "must be a number, got " + type_of(j));
  const double x = j.template get<double>();
  if (!(std::isfinite(x) && x > 0.0)) fail(path, "must be finite and > 0, got " + format_number(x));
  return x;
}

template <class Json>
double BasicJsonSchema<Json>::in_range(const json& j, const std::string& path, double lo, double hi,
                            bool open) const {
  const double x = finite_number(j, path);
  const bool ok = open ? (x > lo && x < hi) : (x >= lo && x <= hi);
  if (!ok)
    fail(path, "must be in " + std::string(open ? "(" : "[") + format_number(lo) + ", " +
                   format_number(hi) + (open ? ")" : "]") + ", got " + format_number(x));
  return x;
}

template <class Json>
long long BasicJsonSchema<Json>::integer(const json& j, const std::string& path, long long lo,
                              long long hi) const {
  const double x = j.is_number() ? j.template get<double>() : 0.0;
  if (!j.is_number_integer() && !(j.is_number_float() && std::floor(x) == x))
    fail(path, "must be an integer, got " + (j.is_number() ? format_number(x) : type_of(j)));
  if (!(x >= static_cast<double>(lo) && x <= static_cast<double>(hi)))
    fail(path, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                   "], got " + format_number(x));
  return static_cast<long long>(x);
}

template <class Json>
void BasicJsonSchema<Json>::non_empty_array(const json& j, const std::string& path, const std::string& of) const {
  if (!j.is_array() || j.empty())
    fail(path, "must be a non-empty array" + of + ", got " +
                   (j.is_array() ? std::string("[]") : type_of(j)));
}

template <class Json>
std::vector<std::string> BasicJsonSchema<Json>::non_empty_strings(const json& j,
                                                                  const std::string& path) const {
  non_empty_array(j, path, " of strings");
  std::vector<std::string> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) out.push_back(non_empty_string(j[i], index_path(path, i)));
  return out;
}

template <class Json>
void BasicJsonSchema<Json>::array_of_size(const json& j, const std::string& path, std::size_t n,
                               const std::string& what) const {
  if (!j.is_array() || j.size() != n)
    fail(path, "must be " + what + ", got " +
                   (j.is_array() ? "an array of " + std::to_string(j.size()) : type_of(j)));
}

template <class Json>
Vec3 BasicJsonSchema<Json>::vec3(const json& j, const std::string& path) const {
  array_of_size(j, path, 3, "an array of 3 numbers [x, y, z]");
  return Vec3(finite_number(j[0], index_path(path, 0)), finite_number(j[1], index_path(path, 1)),
              finite_number(j[2], index_path(path, 2)));
}

template <class Json>
Vec3 BasicJsonSchema<Json>::direction(const json& j, const std::string& path) const {
  const Vec3 v = vec3(j, path);
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) fail(path, "must be a non-zero finite direction");
  return v / n;
}

template <class Json>
Rgb BasicJsonSchema<Json>::rgb(const json& j, const std::string& path) const {
  array_of_size(j, path, 3, "an array of 3 numbers [r, g, b]");
  Rgb out{};
  for (std::size_t c = 0; c < 3; ++c) out[c] = non_negative(j[c], index_path(path, c));
  return out;
}

template <class Json>
PiecewiseLinear BasicJsonSchema<Json>::points(const json& j, const std::string& path) const {
  non_empty_array(j, path, " of [scalar, value] points");
  PiecewiseLinear f;
  f.scalar.reserve(j.size());
  f.value.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) {
    const json& p = j[i];
    const std::string ppath = index_path(path, i);
    array_of_size(p, ppath, 2, "a [scalar, value] pair");
    const double s = finite_number(p[0], index_path(ppath, 0));
    const double v = non_negative(p[1], index_path(ppath, 1));
    // A scalar may repeat once: the two points are a jump's left and right values.
    if (i > 0 && !(s >= f.scalar.back()))
      fail(index_path(ppath, 0), "scalar points must be non-decreasing (" +
                                     format_number(s) + " after " +
                                     format_number(f.scalar.back()) + ")");
    if (i > 1 && s == f.scalar[i - 2])
      fail(index_path(ppath, 0), "scalar " + format_number(s) +
                                     " appears three times (at most twice: a jump's left and right values)");
    f.scalar.push_back(s);
    f.value.push_back(v);
  }
  return f;
}

template <class Json>
std::array<PiecewiseLinear, kChannels> BasicJsonSchema<Json>::channels(const json& j,
                                                            const std::string& path) const {
  if (j.is_array()) {
    const PiecewiseLinear f = points(j, path);
    return {f, f, f};
  }
  if (!j.is_object())
    fail(path, "must be a list of [scalar, value] points or an object with keys r, g, b, got " +
                   type_of(j));
  check_fields(j, path, {"r", "g", "b"});
  std::array<PiecewiseLinear, kChannels> out;
  const char* keys[kChannels] = {"r", "g", "b"};
  for (int c = 0; c < kChannels; ++c)
    out[c] = points(required(j, path, keys[c]), member_path(path, keys[c]));
  return out;
}

template <class Json>
TransferFunctions BasicJsonSchema<Json>::transfer_functions(const json& j, const std::string& path) const {
  require_object(j, path);
  if (j.find("paraview_preset") != j.end()) return preset_transfer_functions(j, path);
  check_fields(j, path, {"density", "color"});
  TransferFunctions tf;
  tf.density = channels(required(j, path, "density"), member_path(path, "density"));
  tf.color = channels(required(j, path, "color"), member_path(path, "color"));
  return tf;
}

// {"paraview_preset": FILE (relative to this file), "name"?, "index"?, "convention"?, "unit_distance"? |
// "sample_distance"?, "tolerance"?, "opacity"?, "range"?}: the preset imported as `rayint tf
// import` does (input/paraview_preset.hpp, docs/transfer-function-conventions.md).
template <class Json>
TransferFunctions BasicJsonSchema<Json>::preset_transfer_functions(const json& j,
                                                                   const std::string& path) const {
  return import_paraview_preset(preset_import_request(j, path)).result.transfer;
}

template <class Json>
PresetImportRequest BasicJsonSchema<Json>::preset_import_request(const json& j, const std::string& path) const {
  check_fields(j, path, {"paraview_preset", "name", "index", "convention", "unit_distance", "sample_distance",
                         "tolerance", "opacity", "range"});
  PresetImportRequest r;
  const std::string file = non_empty_string(required(j, path, "paraview_preset"),
                                            member_path(path, "paraview_preset"));
  const std::filesystem::path fp(file);
  r.file = fp.is_absolute() ? file : (std::filesystem::path(source_).parent_path() / fp).string();
  if (const json* n = optional(j, "name")) r.name = non_empty_string(*n, member_path(path, "name"));
  r.request_source = source_;
  r.index_field = member_path(path, "index");
  if (const json* i = optional(j, "index"))
    r.index = static_cast<std::size_t>(integer(*i, r.index_field, 0, std::numeric_limits<int>::max()));
  r.opacity_field = member_path(path, "opacity");
  r.distance_field = member_path(path, "unit_distance");
  r.range_field = member_path(path, "range");
  r.tolerance_field = member_path(path, "tolerance");
  const json* unit = optional(j, "unit_distance");
  const json* sample = optional(j, "sample_distance");
  if (unit != nullptr && sample != nullptr)
    fail(path, "give at most one of unit_distance and sample_distance");
  if (const json* c = optional(j, "convention")) {
    const std::string cpath = member_path(path, "convention");
    const auto conv = parse_convention(string_value(*c, cpath));
    if (!conv) fail(cpath, "must be density, unit_distance, sample_distance or nerf_sigma");
    r.options.convention = *conv;
  }
  if (unit != nullptr) {
    r.options.distance = positive(*unit, r.distance_field);
    r.options.convention = OpacityConvention::unit_distance;
  }
  if (sample != nullptr) {
    r.distance_field = member_path(path, "sample_distance");
    r.options.distance = positive(*sample, r.distance_field);
    r.options.convention = OpacityConvention::sample_distance;
  }
  if (const json* t = optional(j, "tolerance")) r.options.tolerance = positive(*t, member_path(path, "tolerance"));
  if (const json* a = optional(j, "opacity")) r.constant_opacity = non_negative(*a, r.opacity_field);
  if (const json* rg = optional(j, "range")) {
    const std::string rpath = member_path(path, "range");
    array_of_size(*rg, rpath, 2, "a [lo, hi] pair");
    r.range = std::array<double, 2>{finite_number((*rg)[0], index_path(rpath, 0)),
                                    finite_number((*rg)[1], index_path(rpath, 1))};
  }
  return r;
}

template <class Json>
Camera BasicJsonSchema<Json>::camera(const json& j, const std::string& path) const {
  require_object(j, path);
  check_fields(j, path, {"position", "look_at", "up", "fov_deg", "ortho_height", "width", "height"});
  Camera cam;
  cam.position = vec3(required(j, path, "position"), member_path(path, "position"));
  cam.look_at = vec3(required(j, path, "look_at"), member_path(path, "look_at"));
  if (const json* up = optional(j, "up")) cam.up = vec3(*up, member_path(path, "up"));
  const json* fov = optional(j, "fov_deg");
  const json* ortho = optional(j, "ortho_height");
  if ((fov != nullptr) == (ortho != nullptr))
    fail(path, "give exactly one of fov_deg (perspective) or ortho_height (orthographic)");
  if (fov != nullptr) {
    cam.projection = Camera::Projection::perspective;
    cam.fov_deg = in_range(*fov, member_path(path, "fov_deg"), 0.0, 180.0, /*open=*/true);
  } else {
    cam.projection = Camera::Projection::orthographic;
    cam.ortho_height = positive(*ortho, member_path(path, "ortho_height"));
  }
  cam.width = static_cast<int>(integer(required(j, path, "width"), member_path(path, "width"), 1, 16384));
  cam.height = static_cast<int>(integer(required(j, path, "height"), member_path(path, "height"), 1, 16384));
  try {
    cam.validate();
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  return cam;
}

template class BasicJsonSchema<nlohmann::json>;
template class BasicJsonSchema<nlohmann::ordered_json>;

}  // namespace rayint
