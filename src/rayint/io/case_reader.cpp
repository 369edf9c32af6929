// Reading and validating case files (format: cases/README.md).
//
// Two stages:
//  1. json_source::parse (io/json_source.hpp) turns the text into a nlohmann::json tree,
//     reporting duplicate keys, overflowing numbers and syntax errors at their field or line.
//  2. A strict schema walk over the tree: required fields, types, finite and non-negative
//     values, strictly increasing breakpoints, non-empty arrays, and no unknown fields.
//
// Every problem is thrown as one InputError line `<source>: <field path>: <what>`.
#include "rayint/io/case_reader.hpp"

#include "rayint/io/json_source.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace rayint {
namespace {

using nlohmann::json;

using namespace json_source;  // parse, fail, paths, format_number

// ---------------------------------------------------------------------------------------------
// Stage 2: schema.

class CaseSchema {
 public:
  explicit CaseSchema(const std::string& source) : source_(source) {}

  Case read(const json& root) const {
    const std::string path;
    require_object(root, path);
    check_fields(root, path, {"name", "description", "transfer_function", "rays"});
    Case c;
    c.source = source_;
    c.name = non_empty_string(required(root, path, "name"), "name");
    if (root.contains("description")) {
      const json& d = root.at("description");
      if (!d.is_string()) fail(source_, "description", "must be a string, got " + type_of(d));
      c.description = d.get<std::string>();
    }
    c.transfer = transfer_functions(required(root, path, "transfer_function"), "transfer_function");
    c.rays = rays(required(root, path, "rays"), "rays");
    return c;
  }

 private:
  static std::string type_of(const json& j) { return j.type_name(); }

  static std::string join(std::initializer_list<const char*> names) {
    std::string s;
    for (const char* n : names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
  }

  void require_object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(source_, path, "must be an object, got " + type_of(j));
  }

  // Strict: every key must be one of `allowed`. Reported before missing fields, so a typo
  // ("segmnts") is named as such rather than as a missing "segments".
  void check_fields(const json& object, const std::string& path,
                    std::initializer_list<const char*> allowed) const {
    for (const auto& item : object.items()) {
      bool known = false;
      for (const char* a : allowed) known = known || item.key() == a;
      if (!known)
        fail(source_, member_path(path, item.key()),
             "unknown field (expected " + join(allowed) + ")");
    }
  }

  const json& required(const json& object, const std::string& path, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(source_, member_path(path, key), "missing required field");
    return *it;
  }

  std::string non_empty_string(const json& j, const std::string& path) const {
    if (!j.is_string() || j.get_ref<const std::string&>().empty())
      fail(source_, path,
           "must be a non-empty string, got " + (j.is_string() ? std::string("\"\"") : type_of(j)));
    return j.get<std::string>();
  }

  double finite_number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(source_, path, "must be a number, got " + type_of(j));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(source_, path, "must be finite, got " + format_number(x));
    return x;
  }

  double non_negative(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(source_, path, "must be a number, got " + type_of(j));
    const double x = j.get<double>();
    if (!(std::isfinite(x) && x >= 0.0))
      fail(source_, path, "must be finite and >= 0, got " + format_number(x));
    return x + 0.0;  // -0 becomes +0
  }

  void non_empty_array(const json& j, const std::string& path, const std::string& of) const {
    if (!j.is_array() || j.empty())
      fail(source_, path,
           "must be a non-empty array" + of + ", got " +
               (j.is_array() ? std::string("[]") : type_of(j)));
  }

  // [[scalar, value], ...]: scalars finite and strictly increasing, values finite and >= 0.
  PiecewiseLinear points(const json& j, const std::string& path) const {
    non_empty_array(j, path, " of [scalar, value] points");
    PiecewiseLinear f;
    f.scalar.reserve(j.size());
    f.value.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) {
      const json& p = j[i];
      const std::string ppath = index_path(path, i);
      if (!p.is_array() || p.size() != 2)
        fail(source_, ppath,
             "must be a [scalar, value] pair, got " +
                 (p.is_array() ? "an array of " + std::to_string(p.size()) : type_of(p)));
      const double s = finite_number(p[0], index_path(ppath, 0));
      const double v = non_negative(p[1], index_path(ppath, 1));
      if (i > 0 && !(s > f.scalar.back()))
        fail(source_, index_path(ppath, 0),
             "scalar points must be strictly increasing (" + format_number(s) + " after " +
                 format_number(f.scalar.back()) + ")");
      f.scalar.push_back(s);
      f.value.push_back(v);
    }
    return f;
  }

  // Shared form: one list for all three channels; per-channel form: {"r": ..., "g": ..., "b": ...}.
  std::array<PiecewiseLinear, kChannels> channels(const json& j, const std::string& path) const {
    if (j.is_array()) {
      const PiecewiseLinear f = points(j, path);
      return {f, f, f};
    }
    if (!j.is_object())
      fail(source_, path,
           "must be a list of [scalar, value] points or an object with keys r, g, b, got " +
               type_of(j));
    check_fields(j, path, {"r", "g", "b"});
    std::array<PiecewiseLinear, kChannels> out;
    const char* keys[kChannels] = {"r", "g", "b"};
    for (int c = 0; c < kChannels; ++c)
      out[c] = points(required(j, path, keys[c]), member_path(path, keys[c]));
    return out;
  }

  TransferFunctions transfer_functions(const json& j, const std::string& path) const {
    require_object(j, path);
    check_fields(j, path, {"density", "color"});
    TransferFunctions tf;
    tf.density = channels(required(j, path, "density"), member_path(path, "density"));
    tf.color = channels(required(j, path, "color"), member_path(path, "color"));
    return tf;
  }

  Segment segment(const json& j, const std::string& path) const {
    require_object(j, path);
    check_fields(j, path, {"length", "scalar"});
    Segment seg;
    seg.length = non_negative(required(j, path, "length"), member_path(path, "length"));
    const std::string spath = member_path(path, "scalar");
    const json& s = required(j, path, "scalar");
    if (!s.is_array() || s.size() != 2)
      fail(source_, spath,
           "must be a [far, near] pair of numbers, got " +
               (s.is_array() ? "an array of " + std::to_string(s.size()) : type_of(s)));
    seg.scalar_far = finite_number(s[0], index_path(spath, 0));
    seg.scalar_near = finite_number(s[1], index_path(spath, 1));
    return seg;
  }

  Ray ray(const json& j, const std::string& path) const {
    require_object(j, path);
    check_fields(j, path, {"background", "segments"});
    Ray r;
    if (j.contains("background")) {
      const std::string bpath = member_path(path, "background");
      const json& b = j.at("background");
      if (!b.is_array() || b.size() != kChannels)
        fail(source_, bpath,
             "must be an array of 3 numbers [r, g, b], got " +
                 (b.is_array() ? "an array of " + std::to_string(b.size()) : type_of(b)));
      for (int c = 0; c < kChannels; ++c)
        r.background[c] = non_negative(b[c], index_path(bpath, static_cast<std::size_t>(c)));
    }
    const std::string spath = member_path(path, "segments");
    const json& segs = required(j, path, "segments");
    non_empty_array(segs, spath, "");
    r.segments.reserve(segs.size());
    for (std::size_t i = 0; i < segs.size(); ++i)
      r.segments.push_back(segment(segs[i], index_path(spath, i)));
    return r;
  }

  std::vector<Ray> rays(const json& j, const std::string& path) const {
    non_empty_array(j, path, "");
    std::vector<Ray> out;
    out.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(ray(j[i], index_path(path, i)));
    return out;
  }

  const std::string& source_;
};

}  // namespace

Case parse_case_text(std::string_view text, const std::string& source) {
  return CaseSchema(source).read(json_source::parse(text, source));
}

Case read_case_file(const std::string& path) {
  const std::string text = json_source::read_text_file(path);
  return parse_case_text(text, path);
}

std::vector<std::string> list_case_files(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::string> files;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() == ".json" && p.filename() != kGateConfigName && it->is_regular_file(ec))
      files.push_back(p.string());
  }
  if (ec) throw InputError(dir + ": cannot list folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace rayint
