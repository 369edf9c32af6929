#include "rayint/core/error.hpp"

#include <nlohmann/json.hpp>

namespace rayint::field {

// Messages are one line: control characters (e.g. from a file name) become spaces.
std::string one_line(std::string s) {
  for (char& ch : s)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = ' ';
  return s;
}

[[noreturn]] void fail(const std::string& source, const std::string& path,
                       const std::string& what) {
  throw InputError(one_line(source + ": " + (path.empty() ? "(root)" : path) + ": " + what));
}

std::string member_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// A user string inside a message: JSON-quoted (so escapes stay on one line), at most ~60 chars.
std::string quoted(const std::string& s) {
  using nlohmann::json;
  constexpr std::size_t kMax = 60;
  std::string cut = s.size() > kMax ? s.substr(0, kMax) : s;
  std::string q = json(cut).dump(-1, ' ', false, json::error_handler_t::replace);
  if (s.size() > kMax) q += "...";
  return q;
}

}  // namespace rayint::field
