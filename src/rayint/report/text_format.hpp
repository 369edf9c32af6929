#pragma once
// Numbers as the text reports (tables, summary lines) print them.
#include <string>

namespace rayint {

std::string g3(double x);                               // printf "%.3g"
std::string printf_number(const char* format, double x);  // printf with one double, e.g. "%.3f"

}  // namespace rayint
