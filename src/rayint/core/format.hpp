#pragma once
// Numbers as rayint prints them in messages and reports.
#include <string>

namespace rayint {

// The shortest decimal that reads back as the same double (std::to_chars), e.g. "0.1", "1e-300".
std::string format_number(double x);

}  // namespace rayint
