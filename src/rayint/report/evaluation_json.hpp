#pragma once
// The one place where evaluation results become JSON. Non-finite numbers are written as null
// (JSON has no NaN/Inf) and flagged with "finite": false.
#include <nlohmann/json.hpp>
#include <vector>

#include "rayint/studies/evaluate.hpp"

namespace rayint {

nlohmann::json number_or_null(double x);
nlohmann::json rgb_json(const Rgb& v);
nlohmann::json to_json(const Diagnostics& d);
nlohmann::json to_json(const ReferenceRay& ref);
nlohmann::json to_json(const MethodOutcome& o);
nlohmann::json to_json(const TetRepairs& r);  // a mesh case's reoriented / dropped tets
nlohmann::json to_json(const CaseEvaluation& c);
nlohmann::json eval_report_json(const std::vector<CaseEvaluation>& cases);

}  // namespace rayint
