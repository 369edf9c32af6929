#pragma once
// What every fuzz target checks of a refusal, and how it reports a finding: each check traps
// (__builtin_trap), so libFuzzer saves the input as a crash artifact. A refusal must be one
// InputError line starting "<source>: " (the file it names, as the CLI prints it).
#include <string>

#include "rayint/core/error.hpp"

namespace rayint::fuzz {

inline void require(bool ok) {
  if (!ok) __builtin_trap();
}

// `what` is one line (no CR or LF) starting "<source>: ".
inline void check_message(const std::string& what, const std::string& source) {
  const std::string prefix = source + ": ";
  require(what.compare(0, prefix.size(), prefix) == 0);
  require(what.find('\n') == std::string::npos && what.find('\r') == std::string::npos);
}

// Runs `body` (a reader on the input, then the checks of what it accepted); an InputError it
// throws must be one line starting "<source>: ". Returns 0, libFuzzer's "go on".
template <class Body>
int refusals_are_one_line(const std::string& source, Body&& body) {
  try {
    body();
  } catch (const InputError& e) {
    check_message(e.what(), source);
  }
  return 0;
}

}  // namespace rayint::fuzz
