#include "rayint/core/output_dir.hpp"

#include <filesystem>
#include <system_error>

#include "rayint/core/error.hpp"

namespace rayint {

void ensure_output_directory(const std::string& dir, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw InputError(dir + ": " + option + ": exists and is not a directory");
    return;
  }
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw InputError(dir + ": " + option + ": cannot create the directory (" +
                     (ec ? ec.message() : std::string("a parent is not a directory")) + ")");
}

void require_input_directory(const std::string& dir, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) throw InputError(dir + ": " + option + ": no such directory");
  if (!fs::is_directory(st)) throw InputError(dir + ": " + option + ": exists and is not a directory");
}

}  // namespace rayint
