#pragma once
// The text forms of `rayint stress`: the table of errors per regime and method, and the progress
// line on stderr (studies/stress.hpp).
#include <string>

#include "rayint/studies/stress.hpp"

namespace rayint {

std::string stress_table(const StressReport& report);
std::string stress_progress_line(const StressProgress& progress);

}  // namespace rayint
