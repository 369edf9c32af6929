#pragma once
// The JSON of a `rayint cells` report (studies/cells_study.hpp). Non-finite numbers are null.
#include <nlohmann/json.hpp>

#include "rayint/studies/cells_study.hpp"

namespace rayint {

nlohmann::ordered_json to_json(const CellsReport& report);

}  // namespace rayint
