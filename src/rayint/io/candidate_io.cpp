// Candidate files for `rayint check` and the check's JSON diff (docs/candidate-format.md).
//
// Reading has the same two stages as the case reader (io/case_reader.cpp):
//  1. a SAX pass builds a nlohmann::json tree while tracking the field path of the value being
//     read, so that duplicate keys (which nlohmann's DOM parser resolves silently to the last)
//     and numbers that overflow a double (1e999, nlohmann's out_of_range.406) are reported at
//     their field, and syntax errors keep nlohmann's line, column and reason;
//  2. a strict schema walk: known fields only, types, three finite numbers per ray.
// Matching against the case (name, ray count) is a separate step, require_candidate_matches.
// Every problem is one InputError line `<source>: <field path>: <what>`.
#include "rayint/io/candidate_io.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

namespace rayint {
namespace {

using nlohmann::json;

constexpr const char* kChannelNames[kChannels] = {"r", "g", "b"};

// Messages are one line: control characters (e.g. from a file name) become spaces.
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

// A user string inside a message: JSON-quoted (so escapes stay on one line), at most ~60 chars.
std::string quoted(const std::string& s) {
  constexpr std::size_t kMax = 60;
  std::string cut = s.size() > kMax ? s.substr(0, kMax) : s;
  std::string q = json(cut).dump(-1, ' ', false, json::error_handler_t::replace);
  if (s.size() > kMax) q += "...";
  return q;
}

// Shortest decimal that reads back as the same double.
std::string format_number(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

// ---------------------------------------------------------------------------------------------
// Stage 1: SAX builder with field paths.

class PathTrackingBuilder final : public json::json_sax_t {
 public:
  PathTrackingBuilder(std::string_view text, const std::string& source)
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
    open(json(json::value_t::object), false);
    return true;
  }
  bool key(string_t& val) override {
    frames_.back().key = val;
    json& object = *frames_.back().container;
    if (object.contains(val)) fail(source_, path(), "duplicate field");
    member_ = &object[val];
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t /*elements*/) override {
    open(json(json::value_t::array), true);
    return true;
  }
  bool end_array() override { return close(); }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const json::exception& ex) override {
    // out_of_range.406: a number that overflows a double; the path of the value is current.
    if (ex.id == 406) fail(source_, path(), "must be finite, got " + last_token);
    fail(source_, "", syntax_message(position, ex.what()));
  }

 private:
  struct Frame {
    json* container;
    bool is_array;
    std::string key;        // object: key of the value being read
    std::size_t index = 0;  // array: index of the value being read
  };

  // "invalid JSON at line L, column C: <nlohmann's reason>"; `position` counts the characters
  // read, the last of which is the offending one.
  std::string syntax_message(std::size_t position, const std::string& what) const {
    const std::size_t at = std::min(position > 0 ? position - 1 : 0, text_.size());
    const auto line = 1 + std::count(text_.begin(), text_.begin() + static_cast<long>(at), '\n');
    const std::size_t newline = at == 0 ? std::string_view::npos : text_.rfind('\n', at - 1);
    const std::size_t column = at - (newline == std::string_view::npos ? 0 : newline + 1) + 1;
    std::string reason = what;
    const auto col = what.find("column ");
    const auto colon = col == std::string::npos ? std::string::npos : what.find(": ", col);
    if (colon != std::string::npos)
      reason = what.substr(colon + 2);
    else if (const auto bracket = what.find("] "); bracket != std::string::npos)
      reason = what.substr(bracket + 2);
    return "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
           ": " + reason;
  }

  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) p = f.is_array ? index_path(p, f.index) : member_path(p, f.key);
    return p;
  }

  // Stores `value` where the parser is and returns its address.
  json* place(json value) {
    if (frames_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Frame& f = frames_.back();
    if (f.is_array) {
      f.container->push_back(std::move(value));
      return &f.container->back();
    }
    *member_ = std::move(value);
    return member_;
  }

  void open(json value, bool is_array) {
    json* where = place(std::move(value));
    frames_.push_back(Frame{where, is_array, {}, 0});
  }

  // A value is complete: an enclosing array moves on to its next index.
  bool add(json value) {
    place(std::move(value));
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
    return true;
  }

  bool close() {
    frames_.pop_back();
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
    return true;
  }

  std::string_view text_;
  const std::string& source_;
  json root_;
  std::vector<Frame> frames_;  // containers being filled; pointers stay valid (see place)
  json* member_ = nullptr;
};

// ---------------------------------------------------------------------------------------------
// Stage 2: schema.

class CandidateSchema {
 public:
  explicit CandidateSchema(const std::string& source) : source_(source) {}

  Candidate read(const json& root) const {
    require_object(root, "");
    check_fields(root, "", {"case", "renderer", "rays"});
    Candidate c;
    c.source = source_;
    c.case_name = non_empty_string(required(root, "", "case"), "case");
    if (const auto it = root.find("renderer"); it != root.end()) {
      if (!it->is_string())
        fail(source_, "renderer", "must be a string, got " + std::string(it->type_name()));
      c.renderer = it->get<std::string>();
    }
    const json& rays = required(root, "", "rays");
    if (!rays.is_array() || rays.empty())
      fail(source_, "rays",
           "must be a non-empty array of {\"intensity\": [r, g, b]}, one per ray of the case, "
           "got " +
               (rays.is_array() ? std::string("[]") : std::string(rays.type_name())));
    c.intensity.reserve(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      c.intensity.push_back(ray(rays[i], index_path("rays", i), i));
    return c;
  }

 private:
  void require_object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(source_, path, "must be an object, got " + std::string(j.type_name()));
  }

  void check_fields(const json& object, const std::string& path,
                    std::initializer_list<const char*> allowed) const {
    for (const auto& item : object.items()) {
      if (std::none_of(allowed.begin(), allowed.end(),
                       [&](const char* a) { return item.key() == a; })) {
        std::string names;
        for (const char* a : allowed) names += (names.empty() ? "" : ", ") + std::string(a);
        fail(source_, member_path(path, item.key()), "unknown field (expected " + names + ")");
      }
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
           "must be a non-empty string, got " +
               (j.is_string() ? std::string("\"\"") : std::string(j.type_name())));
    return j.get<std::string>();
  }

  Rgb ray(const json& j, const std::string& path, std::size_t position) const {
    require_object(j, path);
    check_fields(j, path, {"index", "intensity"});
    if (const auto it = j.find("index"); it != j.end()) {
      const bool ok = it->is_number_unsigned() && it->get<std::size_t>() == position;
      if (!ok)
        fail(source_, member_path(path, "index"),
             "must be " + std::to_string(position) +
                 " (entries follow the case's rays in order), got " + it->dump());
    }
    const std::string ipath = member_path(path, "intensity");
    const json& v = required(j, path, "intensity");
    if (!v.is_array() || v.size() != kChannels)
      fail(source_, ipath,
           "must be an array of 3 numbers [r, g, b], got " +
               (v.is_array() ? "an array of " + std::to_string(v.size())
                             : std::string(v.type_name())));
    Rgb out{};
    for (std::size_t k = 0; k < kChannels; ++k) {
      const json& x = v[k];
      const std::string xpath = index_path(ipath, k);
      if (x.is_null())
        fail(source_, xpath, "must be a finite number, got null (JSON has no NaN or Inf)");
      if (!x.is_number())
        fail(source_, xpath, "must be a finite number, got " + std::string(x.type_name()));
      out[k] = x.get<double>();
      if (!std::isfinite(out[k]))
        fail(source_, xpath, "must be a finite number, got " + format_number(out[k]));
    }
    return out;
  }

  const std::string& source_;
};

// ---------------------------------------------------------------------------------------------
// The diff.

using ojson = nlohmann::ordered_json;

ojson number_or_null(double x) { return std::isfinite(x) ? ojson(x) : ojson(nullptr); }

ojson channel_json(const ChannelCheck& ch, int k, bool with_reference) {
  ojson j = {{"channel", kChannelNames[k]},
             {"pass", ch.pass},
             {"expected", number_or_null(ch.expected)},
             {"got", number_or_null(ch.got)},
             {"abs_error", number_or_null(ch.abs_error)},
             {"rel_error", number_or_null(ch.rel_error)},
             {"allowed", number_or_null(ch.allowed)}};
  if (with_reference) {
    j["reference"] = number_or_null(ch.reference);
    j["expected_error"] = number_or_null(ch.expected_error);
  }
  return j;
}

}  // namespace

Candidate parse_candidate_text(std::string_view text, const std::string& source) {
  PathTrackingBuilder builder(text, source);
  json::sax_parse(text.begin(), text.end(), &builder, json::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/false);
  return CandidateSchema(source).read(builder.take_root());
}

void require_candidate_matches(const Candidate& candidate, const Case& c) {
  if (candidate.case_name != c.name)
    fail(candidate.source, "case",
         "is " + quoted(candidate.case_name) + " but the case file " + c.source + " is named " +
             quoted(c.name));
  if (candidate.intensity.size() != c.rays.size())
    fail(candidate.source, "rays",
         "has " + std::to_string(candidate.intensity.size()) + " entries but the case file " +
             c.source + " has " + std::to_string(c.rays.size()) +
             " rays (one entry per ray, in order)");
}

Candidate read_candidate_file(const std::string& path, const Case& c) {
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
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
  Candidate candidate = parse_candidate_text(text, path);
  require_candidate_matches(candidate, c);
  return candidate;
}

nlohmann::ordered_json check_report_json(const CheckResult& r) {
  const CheckSummary& s = r.summary;
  const bool with_ref = r.options.with_reference;
  ojson summary = {{"rays", s.rays},
                   {"failed_rays", s.failed_rays},
                   {"channels", s.channels},
                   {"failed_channels", s.failed_channels},
                   {"max_abs_error", number_or_null(s.max_abs_error)},
                   {"max_rel_error", number_or_null(s.max_rel_error)},
                   {"worst", {{"ray", s.worst_ray}, {"channel", kChannelNames[s.worst_channel]}}}};
  if (with_ref)
    summary["expected_max_rel_uncertainty"] = number_or_null(s.expected_max_rel_uncertainty);
  ojson rays = ojson::array();
  for (std::size_t i = 0; i < r.rays.size(); ++i) {
    ojson channels = ojson::array();
    for (int k = 0; k < kChannels; ++k)
      channels.push_back(channel_json(r.rays[i].channel[static_cast<std::size_t>(k)], k, with_ref));
    rays.push_back({{"index", i}, {"pass", r.rays[i].pass}, {"channels", channels}});
  }
  return {{"tool", "rayint"},
          {"report", "check"},
          {"pass", r.pass},
          {"case", {{"name", r.case_name}, {"file", r.case_source}}},
          {"candidate", {{"file", r.candidate_source}, {"renderer", r.renderer}}},
          {"expected", "exact"},
          {"rule",
           "pass if |got - expected| <= max(abs_tol, rel_tol * |expected|) "
           "for every channel of every ray"},
          {"tolerance", {{"rel", r.options.rel_tol}, {"abs", r.options.abs_tol}}},
          {"summary", summary},
          {"rays", rays}};
}

}  // namespace rayint
