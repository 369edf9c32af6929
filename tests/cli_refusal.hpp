#pragma once
// A command line the CLI must refuse as bad input, checked the same way by every CLI test.
#include <set>
#include <string>

#include "cli_harness.hpp"

namespace rayint::test {

// Runs `args` in `dir` and checks it is refused as bad input: exit 2, one stderr line, and the
// folder as it was (no output, no temporary file left). Returns the run for further checks.
inline CliRun check_refused(const TempDir& dir, const std::string& args) {
  const std::set<std::string> before = dir.entries();
  const CliRun r = run_cli(dir.path, args);
  INFO("rayint " << args << "\nstdout: " << r.out << "\nstderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(line_count(r.err) == 1);
  CHECK(dir.entries() == before);
  return r;
}

}  // namespace rayint::test
