#include "rayint/input/candidate_schema.hpp"

#include <cmath>

#include "rayint/input/json_source.hpp"

namespace rayint::candidate_schema {

using nlohmann::json;
using json_source::index_path;
using json_source::member_path;

double finite(const JsonSchema& s, const json& x, const std::string& path) {
  if (x.is_null()) s.fail(path, "must be a finite number, got null (JSON has no NaN or Inf)");
  if (!x.is_number()) s.fail(path, "must be a finite number, got " + std::string(x.type_name()));
  const double v = x.get<double>();
  if (!std::isfinite(v)) s.fail(path, "must be a finite number, got " + json_source::format_number(v));
  return v;
}

double finite_or_null(const JsonSchema& s, const json& x, const std::string& path) {
  return x.is_null() ? std::nan("") : finite(s, x, path);
}

Rgb triple(const JsonSchema& s, const json& v, const std::string& path, bool allow_null) {
  s.array_of_size(v, path, kChannels, allow_null ? "an array of 3 numbers (or null) [r, g, b]" : "an array of 3 numbers [r, g, b]");
  Rgb out{};
  for (std::size_t k = 0; k < kChannels; ++k)
    out[k] = allow_null ? finite_or_null(s, v[k], index_path(path, k)) : finite(s, v[k], index_path(path, k));
  return out;
}

Root walk(const JsonSchema& s, const json& root, const char* key, const std::string& of,
          const std::function<void(std::size_t, const json&, const std::string&)>& entry) {
  s.require_object(root, "");
  s.check_fields(root, "", {"case", "renderer", "rays"});
  Root r;
  r.case_name = s.non_empty_string(s.required(root, "", "case"), "case");
  if (const json* renderer = s.optional(root, "renderer")) r.renderer = s.string_value(*renderer, "renderer");
  const json& rays = s.required(root, "", "rays");
  s.non_empty_array(rays, "rays", of);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const std::string path = index_path("rays", i);
    s.require_object(rays[i], path);
    s.check_fields(rays[i], path, {"index", key});
    if (const json* index = s.optional(rays[i], "index")) {
      if (!(index->is_number_unsigned() && index->get<std::size_t>() == i))
        s.fail(member_path(path, "index"),
               "must be " + std::to_string(i) + " (entries follow the case's rays in order), got " + index->dump());
    }
    entry(i, s.required(rays[i], path, key), member_path(path, key));
  }
  return r;
}

void require_case_matches(const std::string& source, const std::string& case_name, std::size_t entries,
                          const std::string& name, const std::string& case_source, std::size_t rays) {
  if (case_name != name)
    json_source::fail(source, "case",
                      "is " + json_source::quoted(case_name) + " but the case file " + case_source + " is named " +
                          json_source::quoted(name));
  if (entries != rays)
    json_source::fail(source, "rays",
                      "has " + std::to_string(entries) + " entries but the case file " + case_source + " has " +
                          std::to_string(rays) + " rays (one entry per ray, in order)");
}

void require_case_matches(const std::string& source, const std::string& case_name, std::size_t entries,
                          const Case& c) {
  require_case_matches(source, case_name, entries, c.name, c.source, c.rays.size());
}

}  // namespace rayint::candidate_schema
