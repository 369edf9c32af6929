#pragma once
// The one place where evaluation results become JSON. Non-finite numbers are written as null
// (JSON has no NaN/Inf) and flagged with "finite": false. A case evaluated without the
// reference (eval --no-reference) says "reference": "skipped", and its rays carry no "reference"
// and its methods no error fields (abs_error, rel_error, ulp_error, transmittance_rel_error).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/report/json_number.hpp"  // number_or_null, rgb_json
#include "rayint/studies/evaluate.hpp"

namespace rayint {

nlohmann::json to_json(const Diagnostics& d);
nlohmann::json to_json(const ReferenceRay& ref);
// with_reference false: without the error fields.
nlohmann::json to_json(const MethodOutcome& o, bool with_reference = true);
nlohmann::json to_json(const TetRepairs& r);  // a mesh case's reoriented / dropped tets
nlohmann::json to_json(const CaseEvaluation& c);
nlohmann::json eval_report_json(const std::vector<CaseEvaluation>& cases);

// One progress line of `rayint eval` on stderr (with its newline), `seconds` since the start:
// "eval NAME: reference 1200000/2000000 segments (60%), 41 s" or
// "eval NAME: method exact, ray 3/10, 45 s".
std::string eval_progress_line(const std::string& case_name, const EvalProgress& p, double seconds);

}  // namespace rayint
