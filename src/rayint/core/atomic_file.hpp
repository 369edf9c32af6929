#pragma once
#include <string>

namespace rayint {

// Writes `content` to `path` through a temporary file in the same directory and a rename, so a
// failure never leaves a partial output file. Throws std::runtime_error naming the path.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace rayint
