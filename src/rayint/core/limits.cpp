#include "rayint/core/limits.hpp"

#include <cerrno>
#include <cstdlib>

#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"

namespace rayint::limits {

std::uint64_t value(const Limit& limit) {
  const char* env = std::getenv(limit.env);
  if (env == nullptr || *env == '\0') return limit.default_value;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(env, &end, 10);
  if (end == env || *end != '\0' || errno != 0 || v == 0 || env[0] == '-')
    throw InputError(field::one_line(std::string(limit.env) + ": must be a whole number >= 1, got '" + env + "'"));
  return static_cast<std::uint64_t>(v);
}

void check(const Limit& limit, double requested, const std::string& where) {
  const std::uint64_t v = value(limit);
  if (requested <= static_cast<double>(v)) return;
  throw InputError(field::one_line(where + ": " + format_number(requested) + " " + limit.what +
                                   " is above the limit of " + format_number(static_cast<double>(v)) + " (" +
                                   limit.env + "=N raises it; docs/limits.md)"));
}

}  // namespace rayint::limits
