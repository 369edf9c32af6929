#pragma once
// Where the bundled cases are: `cases/` of the working directory when there is one (a source
// tree), else the installed copy, <prefix>/share/rayint/cases, found from the executable's own
// path (/proc/self/exe), so an installed `rayint gate` works from any directory.
#include <filesystem>
#include <string>
#include <system_error>

namespace rayint::cli {

// `relative` below the working directory if it exists there, else below the installed data
// folder if it exists there, else `relative` unchanged (its reader then names the missing file).
inline std::string bundled_path(const std::string& relative) {
  namespace fs = std::filesystem;
  if (fs::exists(relative)) return relative;
#ifdef RAYINT_DATA_FROM_BIN
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = (exe.parent_path() / RAYINT_DATA_FROM_BIN / relative).lexically_normal();
    if (fs::exists(installed, ec)) return installed.string();
  }
#endif
  return relative;
}

}  // namespace rayint::cli
