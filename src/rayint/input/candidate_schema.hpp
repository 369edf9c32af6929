#pragma once
// What the two candidate readers share -- input/candidate_reader.cpp (intensities, `rayint
// check`) and input/grad_candidate_reader.cpp (gradients, `rayint gradcheck`): the root
// {"case": NAME, "renderer"?: TEXT, "rays": [{"index"?: i, KEY: ...}, ...]}, the finite-number
// rule with its message for null, and the match of a candidate with its case (name, ray count).
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/input/json_schema.hpp"
#include "rayint/studies/check.hpp"

namespace rayint::candidate_schema {

// A finite number. The message says why JSON cannot carry a NaN or Inf, since a renderer's
// non-finite result usually arrives as null.
double finite(const JsonSchema& s, const nlohmann::json& x, const std::string& path);
// [r, g, b] of finite numbers.
Rgb triple(const JsonSchema& s, const nlohmann::json& v, const std::string& path);

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

}  // namespace rayint::candidate_schema
