#pragma once
// Numbers in every JSON report: a finite value as itself, NaN or infinity (a failed computation,
// or a quantity that does not exist) as null. JSON has no NaN, and a failure must never read as a
// number (issue 30). For nlohmann::json and nlohmann::ordered_json alike.
#include <cmath>
#include <nlohmann/json.hpp>

#include "rayint/model/transfer_function.hpp"  // Rgb

namespace rayint {

template <class Json = nlohmann::json>
Json number_or_null(double x) {
  return std::isfinite(x) ? Json(x) : Json(nullptr);
}

template <class Json = nlohmann::json>
Json rgb_json(const Rgb& v) {
  return Json::array({number_or_null<Json>(v[0]), number_or_null<Json>(v[1]), number_or_null<Json>(v[2])});
}

}  // namespace rayint
