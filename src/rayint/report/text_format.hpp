#pragma once
// Numbers as the text reports (tables, summary lines) print them.
#include <string>

namespace rayint {

std::string g3(double x);                               // printf "%.3g"
std::string printf_number(const char* format, double x);  // printf with one double, e.g. "%.3f"

// printf onto the end of `out`, whatever the text's length: how the tables are written, a line
// (or part of one) at a time.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void appendf(std::string& out, const char* format, ...);

}  // namespace rayint
