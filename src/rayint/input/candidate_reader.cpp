// Candidate files for `rayint check` (docs/candidate-format.md).
//
// Reading has the same two stages as the case reader (input/case_reader.cpp):
//  1. json_source::parse (input/json_source.hpp) turns the text into a nlohmann::json tree,
//     reporting duplicate keys, overflowing numbers and syntax errors at their field or line;
//  2. a strict schema walk with JsonSchema (input/json_schema.hpp): known fields only, types,
//     three finite numbers per ray.
// Matching against the case (name, ray count) is a separate step, require_candidate_matches.
// Every problem is one InputError line `<source>: <field path>: <what>`.
#include "rayint/input/candidate_reader.hpp"

#include <cmath>
#include <utility>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

using json_source::fail;
using json_source::quoted;

namespace {

using nlohmann::json;
using json_source::format_number;
using json_source::index_path;
using json_source::member_path;

// One channel of an intensity. The message says why JSON cannot carry a NaN or Inf, since a
// renderer's non-finite result usually arrives here as null.
double channel(const JsonSchema& s, const json& x, const std::string& path) {
  if (x.is_null()) s.fail(path, "must be a finite number, got null (JSON has no NaN or Inf)");
  if (!x.is_number()) s.fail(path, "must be a finite number, got " + std::string(x.type_name()));
  const double v = x.get<double>();
  if (!std::isfinite(v)) s.fail(path, "must be a finite number, got " + format_number(v));
  return v;
}

// rays[position]: {"index"?: position, "intensity": [r, g, b]}.
Rgb ray(const JsonSchema& s, const json& j, const std::string& path, std::size_t position) {
  s.require_object(j, path);
  s.check_fields(j, path, {"index", "intensity"});
  if (const json* index = s.optional(j, "index")) {
    if (!(index->is_number_unsigned() && index->get<std::size_t>() == position))
      s.fail(member_path(path, "index"),
             "must be " + std::to_string(position) +
                 " (entries follow the case's rays in order), got " + index->dump());
  }
  const std::string ipath = member_path(path, "intensity");
  const json& v = s.required(j, path, "intensity");
  s.array_of_size(v, ipath, kChannels, "an array of 3 numbers [r, g, b]");
  Rgb out{};
  for (std::size_t k = 0; k < kChannels; ++k) out[k] = channel(s, v[k], index_path(ipath, k));
  return out;
}

Candidate read_candidate(const JsonSchema& s, const json& root) {
  s.require_object(root, "");
  s.check_fields(root, "", {"case", "renderer", "rays"});
  Candidate c;
  c.source = s.source();
  c.case_name = s.non_empty_string(s.required(root, "", "case"), "case");
  if (const json* r = s.optional(root, "renderer")) c.renderer = s.string_value(*r, "renderer");
  const json& rays = s.required(root, "", "rays");
  s.non_empty_array(rays, "rays", " of {\"intensity\": [r, g, b]}, one per ray of the case");
  c.intensity.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    c.intensity.push_back(ray(s, rays[i], index_path("rays", i), i));
  return c;
}

}  // namespace

Candidate parse_candidate_text(std::string_view text, const std::string& source) {
  return read_candidate(JsonSchema(source), json_source::parse(text, source));
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
