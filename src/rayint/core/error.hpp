#pragma once
// The one error type every reader throws, and how its message names the place of the problem.
//
// An InputError's message is one line `<file>: <field path>: <what>` (field path "(root)" for the
// whole document), e.g. `cases/x.json: rays[0].segments[1].length: must be finite and >= 0, got
// -1`. The CLI prints it as it is and exits 2 (README, "Exit codes"). Every reader of the library
// (case, candidate, gate, scene, grid, slab, benchmark and mesh readers, and the numerical areas'
// own validation of what they are handed) throws it through the helpers below, so the messages
// have one form.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace rayint {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace field {

std::string one_line(std::string s);  // control characters become spaces
// Throws InputError "<source>: <path>: <what>" ("(root)" for an empty path), on one line.
[[noreturn]] void fail(const std::string& source, const std::string& path, const std::string& what);
std::string member_path(const std::string& path, const std::string& key);  // "a.b"
std::string index_path(const std::string& path, std::size_t i);            // "a[3]"
std::string quoted(const std::string& s);  // JSON-quoted, at most ~60 characters

}  // namespace field
}  // namespace rayint
