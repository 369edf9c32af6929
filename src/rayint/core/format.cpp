#include "rayint/core/format.hpp"

#include <charconv>

namespace rayint {

std::string format_number(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

}  // namespace rayint
