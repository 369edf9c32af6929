#pragma once
// The status line of `rayint check` for CI logs (stderr, so stdout stays the diff).
#include <string>

#include "rayint/studies/check.hpp"

namespace rayint {

std::string check_summary_line(const CheckResult& result);

}  // namespace rayint
