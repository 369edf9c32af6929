#pragma once
// Reading and validating case files (format: cases/README.md). Every problem is reported as an
// InputError whose message is one line naming the file and the JSON field.
#include <stdexcept>
#include <string>
#include <string_view>

#include "rayint/model/ray.hpp"

namespace rayint {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `source` is the file name used in messages. Throws InputError.
Case parse_case_text(std::string_view text, const std::string& source);
Case read_case_file(const std::string& path);

}  // namespace rayint
