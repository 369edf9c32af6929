#pragma once
// Shared by the tests of bad input files (case_reader, check, the CLI, the mesh readers): the
// Fig. 2 case text, a one-place text substitution, the one-line `<file>: <path>: <what>` InputError
// message, and tables of bad inputs with the start of the message each must give.
#include <catch2/catch.hpp>
#include <cstddef>
#include <string>
#include <string_view>

#include "rayint/core/error.hpp"

namespace rayint::test {

// Williams & Max Fig. 2, first interval, as the text of a case file named fig2 (density 5 -> 2
// over the scalar, colour r 1.7, g 1.0, b 0.2) with `rays` (a JSON array) as its rays.
inline std::string fig2_case_text(const std::string& rays) {
  return R"({
  "name": "fig2",
  "transfer_function": {
    "density": [[0.0, 5.0], [1.0, 2.0]],
    "color": {"r": [[0.0, 1.7]], "g": [[0.0, 1.0]], "b": [[0.0, 0.2]]}
  },
  "rays": )" +
         rays + "\n}";
}

// `text` with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string replace_first(std::string text, std::string_view from, std::string_view to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  return text;
}

// The message of the `Error` that `read` throws, or `none` when it throws nothing.
template <class Error, class Read>
std::string error_message_of(Read&& read, const std::string& none) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return none;
}

// The message of the InputError that `read` throws, or "(no error)".
template <class Read>
std::string input_error_of(Read&& read) {
  return error_message_of<InputError>(read, "(no error)");
}

// `msg` is `<source>: <path>: <what...>` on one line.
inline void check_one_line_error(const std::string& msg, const std::string& source,
                                 const std::string& path, const std::string& what) {
  INFO("message: " << msg);
  CHECK(msg.rfind(source + ": " + path + ": ", 0) == 0);
  CHECK(msg.find(what) != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

// A bad input file's text and the start of the message it must be refused with.
struct BadText {
  std::string text, expect;
};

// Every row of `rows` (a bad input and `expect`) refused with one line starting with its
// `expect`: error_of(row) is the message (or "(no error)", which fails).
template <class Row, std::size_t N, class ErrorOf>
void check_refusal_table(const Row (&rows)[N], ErrorOf&& error_of) {
  for (const Row& row : rows) {
    INFO(row.expect);
    const std::string msg = error_of(row);
    INFO("got: " << msg);
    CHECK(msg.rfind(row.expect, 0) == 0);
    CHECK(msg.find('\n') == std::string::npos);
  }
}

}  // namespace rayint::test
