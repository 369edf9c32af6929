#pragma once
// JSON input with field paths: the one place where rayint's input files (cases, candidates) are
// parsed into nlohmann::json, so that every problem can be reported as one line
// `<source>: <field path>: <what>` (InputError). Duplicate keys, which nlohmann's DOM parser
// silently resolves to the last one, and numbers that overflow a double (1e999, nlohmann's
// out_of_range.406) are reported at their field; syntax errors carry the 1-based line and column
// of the offending character and nlohmann's reason. Parsing is strict: no comments, nothing but
// whitespace after the document.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "rayint/io/case_reader.hpp"  // InputError

namespace rayint::json_source {

nlohmann::json parse(std::string_view text, const std::string& source);

// The whole file as text; InputError "<path>: cannot read file (<reason>)".
std::string read_text_file(const std::string& path);

// Message helpers shared by the schema walks.
std::string one_line(std::string s);  // control characters become spaces
[[noreturn]] void fail(const std::string& source, const std::string& path,
                       const std::string& what);  // "(root)" for an empty path
std::string member_path(const std::string& path, const std::string& key);
std::string index_path(const std::string& path, std::size_t i);
std::string quoted(const std::string& s);  // JSON-quoted, at most ~60 characters
std::string format_number(double x);       // shortest decimal that reads back the same

}  // namespace rayint::json_source
