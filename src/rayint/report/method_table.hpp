#pragma once
// `rayint methods`: the method table (integrators/integrator.hpp, method_table()) as text and
// JSON -- every method with its parameters, their types, defaults and allowed values. The same
// table parse_method_spec validates against, so what is listed is what is accepted.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"

namespace rayint {

std::string methods_text(const std::vector<MethodSchema>& methods);
// [{"name", "about", "params": [{"name", "type", "default" (null: none), "allowed",
//   "min", "max", "min_exclusive", "max_exclusive" (numbers) or "choices", "about", "limit"}]}]
nlohmann::json methods_json(const std::vector<MethodSchema>& methods);

}  // namespace rayint
