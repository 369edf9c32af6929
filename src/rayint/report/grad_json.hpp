#pragma once
// The JSON of `rayint grad` and `rayint gradcheck` (issue 28; format: docs/gradients.md).
#include <nlohmann/json.hpp>
#include <vector>

#include "rayint/studies/grad_study.hpp"

namespace rayint {

// One gradient in the layout:
//   {"background": [r, g, b], "length": [[r, g, b] per segment],
//    "scalar": [[[far r, g, b], [exit r, g, b]] per segment],
//    "density": {"r": [[d position, d value] per node of density r], "g": ..., "b": ...},
//    "color": {same}}
// Non-finite numbers are written as null.
nlohmann::ordered_json gradient_json(const RayGradient& g);

// `rayint grad`: per case and ray, the reference gradient and every method's intensity,
// gradient and errors (max relative per channel); a failed method has "gradient": null and
// "error": its message.
nlohmann::ordered_json grad_report_json(const std::vector<GradCaseResult>& cases);

// `rayint gradcheck`: verdict, counts, the rule and the worst entry by name.
nlohmann::ordered_json gradcheck_report_json(const GradCheckResult& r);

}  // namespace rayint
