// Candidate files for `rayint check` and the check's JSON diff (docs/candidate-format.md).
//
// Reading has the same two stages as the case reader (input/case_reader.cpp):
//  1. a SAX pass builds a nlohmann::json tree while tracking the field path of the value being
//     read, so that duplicate keys (which nlohmann's DOM parser resolves silently to the last)
//     and numbers that overflow a double (1e999, nlohmann's out_of_range.406) are reported at
//     their field, and syntax errors keep nlohmann's line, column and reason;
//  2. a strict schema walk: known fields only, types, three finite numbers per ray.
// Matching against the case (name, ray count) is a separate step, require_candidate_matches.
// Every problem is one InputError line `<source>: <field path>: <what>`.
#include "rayint/input/candidate_reader.hpp"

#include "rayint/input/json_source.hpp"

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

using namespace json_source;  // parse, fail, paths, quoted, format_number

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

}  // namespace

Candidate parse_candidate_text(std::string_view text, const std::string& source) {
  return CandidateSchema(source).read(json_source::parse(text, source));
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
  const std::string text = json_source::read_text_file(path);
  Candidate candidate = parse_candidate_text(text, path);
  require_candidate_matches(candidate, c);
  return candidate;
}

}  // namespace rayint
