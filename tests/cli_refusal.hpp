#pragma once
// A command line the CLI must refuse as bad input, checked the same way by every CLI test, and a
// table of them with the stderr lines they must give.
#include <set>
#include <string>
#include <vector>

#include "cli_harness.hpp"

namespace rayint::test {

// Runs `args` in `dir` and checks it is refused as bad input: exit 2, one stderr line, and the
// folder as it was (no output, no temporary file left). Returns the run for further checks.
inline CliRun check_refused(const TempDir& dir, const std::string& args) {
  const std::set<std::string> before = dir.entries();
  const CliRun r = run_cli(dir.path, args);
  INFO("rayint " << args << "\nstdout: " << r.out);
  check_one_line_exit(r);
  CHECK(dir.entries() == before);
  return r;
}

// A command line the CLI must refuse, and its stderr line after "rayint: error: ".
struct Refusal {
  std::string args, message;
};

// Each of `refusals` run in `dir` and refused as check_refused says, with nothing on stdout and
// the stderr line "rayint: error: <message>" followed by anything (`whole_line`: by the newline).
inline void check_refusals(const TempDir& dir, const std::vector<Refusal>& refusals, bool whole_line) {
  for (const Refusal& x : refusals) {
    const CliRun r = check_refused(dir, x.args);
    INFO("rayint " << x.args << "\nstderr: " << r.err);
    CHECK(r.out.empty());
    if (whole_line)
      CHECK(r.err == "rayint: error: " + x.message + "\n");
    else
      CHECK(r.err.rfind("rayint: error: " + x.message, 0) == 0);
  }
}

}  // namespace rayint::test
