// Reading and validating case files (format: cases/README.md).
//
// Two stages:
//  1. A SAX pass (CaseJsonBuilder) turns the text into a nlohmann::json tree while tracking the
//     field path of every value, so that the two problems nlohmann itself would report without
//     a path -- duplicate keys (which its DOM parser silently resolves to the last one) and
//     numbers that overflow a double such as 1e999 (its out_of_range.406) -- are reported at
//     their field. Syntax errors give the 1-based line and column of the offending character
//     and nlohmann's reason.
//  2. A strict schema walk over the tree: required fields, types, finite and non-negative
//     values, strictly increasing breakpoints, non-empty arrays, and no unknown fields.
//
// Every problem is thrown as one InputError line `<source>: <field path>: <what>`.
#include "rayint/io/case_reader.hpp"

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

// Shortest decimal that reads back as the same double ("-1", "0.5", "1e-300", "inf").
std::string format_number(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

// Messages are one line: any control character (e.g. from a file name) becomes a space.
std::string one_line(std::string s) {
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = ' ';
  return s;
}

[[noreturn]] void fail(const std::string& source, const std::string& path,
                       const std::string& what) {
  throw InputError(one_line(source + ": " + (path.empty() ? "(root)" : path) + ": " + what));
}

std::string member_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// ---------------------------------------------------------------------------------------------
// Stage 1: SAX builder with field paths.

class CaseJsonBuilder final : public json::json_sax_t {
 public:
  CaseJsonBuilder(std::string_view text, const std::string& source)
      : text_(text), source_(source) {}

  json take_root() { return std::move(root_); }

  bool null() override { return add(json(nullptr)); }
  bool boolean(bool val) override { return add(json(val)); }
  bool number_integer(number_integer_t val) override { return add(json(val)); }
  bool number_unsigned(number_unsigned_t val) override { return add(json(val)); }
  bool number_float(number_float_t val, const string_t& /*token*/) override {
    return add(json(val));
  }
  bool string(string_t& val) override { return add(json(std::move(val))); }
  bool binary(binary_t& val) override { return add(json(std::move(val))); }

  bool start_object(std::size_t /*elements*/) override {
    stack_.push_back(place(json(json::value_t::object)));
    frames_.push_back(Frame{false, {}, 0});
    return true;
  }

  bool key(string_t& val) override {
    json& object = *stack_.back();
    frames_.back().key = val;
    if (object.contains(val)) fail(source_, path(), "duplicate field");
    object_element_ = &object[val];
    return true;
  }

  bool end_object() override { return close(); }

  bool start_array(std::size_t /*elements*/) override {
    stack_.push_back(place(json(json::value_t::array)));
    frames_.push_back(Frame{true, {}, 0});
    return true;
  }

  bool end_array() override { return close(); }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const json::exception& ex) override {
    // out_of_range.406: a number literal that overflows a double (1e999). nlohmann stops here,
    // before the value is stored, so the path of the value being read is still current.
    if (ex.id == 406) fail(source_, path(), "must be finite, got " + last_token);
    fail(source_, "", invalid_json_message(position, ex.what()));
  }

 private:
  struct Frame {
    bool is_array;
    std::string key;    // object: the key whose value is being read
    std::size_t index;  // array: index of the element being read
  };

  // "invalid JSON at line L, column C: <reason>". `position` counts the characters read, the
  // last of which is the offending one (or the end of the input); L and C are 1-based and point
  // at it. The reason is nlohmann's, from its message
  // "[json.exception.parse_error.101] parse error at line 3, column 7: <reason>".
  std::string invalid_json_message(std::size_t position, const std::string& what) const {
    const std::size_t at = std::min(position > 0 ? position - 1 : 0, text_.size());
    const auto line = 1 + std::count(text_.begin(), text_.begin() + at, '\n');
    const std::size_t newline = at == 0 ? std::string_view::npos : text_.rfind('\n', at - 1);
    const std::size_t line_begin = newline == std::string_view::npos ? 0 : newline + 1;
    const std::size_t column = at - line_begin + 1;
    const auto column_at = what.find("column ");
    const auto colon = column_at == std::string::npos ? column_at : what.find(": ", column_at);
    const auto bracket = what.find("] ");
    const std::string reason = colon != std::string::npos     ? what.substr(colon + 2)
                               : bracket != std::string::npos ? what.substr(bracket + 2)
                                                              : what;
    return "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
           ": " + reason;
  }

  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) p = f.is_array ? index_path(p, f.index) : member_path(p, f.key);
    return p;
  }

  // Stores a value at the current position and returns where it lives.
  json* place(json value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    json& parent = *stack_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    *object_element_ = std::move(value);
    return object_element_;
  }

  // A value is complete: the enclosing array moves on to its next index.
  void finished_value() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }

  bool add(json value) {
    place(std::move(value));
    finished_value();
    return true;
  }

  bool close() {
    stack_.pop_back();
    frames_.pop_back();
    finished_value();
    return true;
  }

  std::string_view text_;
  const std::string& source_;
  json root_;
  std::vector<json*> stack_;
  std::vector<Frame> frames_;
  json* object_element_ = nullptr;
};

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
  CaseJsonBuilder builder(text, source);
  // strict: nothing but whitespace may follow the document; comments are not JSON.
  json::sax_parse(text.begin(), text.end(), &builder, json::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/false);
  return CaseSchema(source).read(builder.take_root());
}

Case read_case_file(const std::string& path) {
  errno = 0;
  struct Close {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  const std::unique_ptr<std::FILE, Close> file(std::fopen(path.c_str(), "rb"));
  auto cannot_read = [&path]() {
    const int err = errno;
    throw InputError(one_line(path + ": cannot read file (" +
                              (err != 0 ? std::strerror(err) : "read error") + ")"));
  };
  if (!file) cannot_read();
  std::string text;
  char buf[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, file.get())) > 0) text.append(buf, n);
  if (std::ferror(file.get())) cannot_read();
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
