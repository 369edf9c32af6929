#pragma once
// What the two candidate readers share -- input/candidate_reader.cpp (intensities, `rayint
// check`) and input/grad_candidate_reader.cpp (gradients, `rayint gradcheck`): the root
// {"case": NAME, "renderer"?: TEXT, "rays": [{"index"?: i, KEY: ...}, ...]}, the finite-number
// rule with its message for null, and the match of a candidate with its case (name, ray count).
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/studies/check.hpp"

namespace rayint::candidate_schema {

// A finite number. The message says why JSON cannot carry a NaN or Inf, since a renderer's
// non-finite result usually arrives as null.
double finite(const JsonSchema& s, const nlohmann::json& x, const std::string& path);
// A finite number, or null (a value the candidate says it cannot give): NaN.
double finite_or_null(const JsonSchema& s, const nlohmann::json& x, const std::string& path);
// [r, g, b] of finite numbers (allow_null: or null, read as NaN).
Rgb triple(const JsonSchema& s, const nlohmann::json& v, const std::string& path, bool allow_null = false);

struct Root {
  std::string case_name, renderer;
};
// Walks the root: known fields, "case", "renderer", and each entry of the non-empty "rays"
// array, an object {"index"?: i, key: value} whose index, if given, is its position; calls
// entry(i, value, path of the value) in order. `of` completes "must be a non-empty array".
Root walk(const JsonSchema& s, const nlohmann::json& root, const char* key, const std::string& of,
          const std::function<void(std::size_t, const nlohmann::json&, const std::string&)>& entry);

// The candidate (file `source`) answers case `c`: the same name and `entries` == its ray count.
void require_case_matches(const std::string& source, const std::string& case_name, std::size_t entries,
                          const Case& c);
// The same against a case given by its name, file and ray count (a mesh case of cells in their
// own interpolation has no segment rays: its evaluation rays, mesh/mesh_case.hpp).
void require_case_matches(const std::string& source, const std::string& case_name, std::size_t entries,
                          const std::string& name, const std::string& case_source, std::size_t rays);

// Parses `text` (file `source`) and walks its root (walk above) into a candidate C (fields
// source, case_name, renderer): entry(s, candidate, value, path) reads each ray's `key` value.
template <class C, class Entry>
C parse(std::string_view text, const std::string& source, const char* key, const std::string& of, Entry&& entry) {
  const JsonSchema s(source);
  C c;
  c.source = source;
  const Root root = walk(s, json_source::parse(text, source), key, of,
                         [&](std::size_t, const nlohmann::json& v, const std::string& path) { entry(s, c, v, path); });
  c.case_name = root.case_name;
  c.renderer = root.renderer;
  return c;
}

// Reads the file `path`, parses it (parse(text, path)) and requires it to match `c`
// (match(candidate, c)): the reading both candidate readers do. Throws InputError.
template <class Parse, class Match>
auto read_file(const std::string& path, const Case& c, Parse&& parse, Match&& match) {
  auto candidate = parse(json_source::read_text_file(path), path);
  match(candidate, c);
  return candidate;
}

}  // namespace rayint::candidate_schema
