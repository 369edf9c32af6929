#pragma once
// The JSON diff of `rayint check` (format: docs/candidate-format.md).
#include <nlohmann/json.hpp>

#include "rayint/studies/check.hpp"

namespace rayint {

// The diff: per ray and channel expected, got, errors, allowance and verdict, plus a summary.
// ordered_json keeps the documented key order (verdict first, rays last) for people reading CI
// logs. Non-finite numbers are written as null.
nlohmann::ordered_json check_report_json(const CheckResult& result);

}  // namespace rayint
