#pragma once
// `rayint converge` as JSON (studies/convergence.hpp). A failed row has "failed": true, its
// reason, and null errors; a fit that could not be made has "order": null and its reason.
#include <nlohmann/json.hpp>

#include "rayint/studies/convergence.hpp"

namespace rayint {

nlohmann::json convergence_json(const ConvergenceResult& r);

}  // namespace rayint
