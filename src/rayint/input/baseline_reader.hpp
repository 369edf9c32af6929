#pragma once
// Reading a drift baseline (format: report/baseline_json.hpp; checks: studies/drift.hpp). Every
// problem is one InputError line `<file>: <field path>: <what>`.
#include <string>
#include <string_view>

#include "rayint/studies/drift.hpp"

namespace rayint {

Baseline parse_baseline_text(std::string_view text, const std::string& source);
Baseline read_baseline_file(const std::string& path);

}  // namespace rayint
