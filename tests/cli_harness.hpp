#pragma once
// Shared by the tests that run the real `rayint` binary (RAYINT_CLI_PATH): a scratch folder
// removed on destruction, a file reader, one CLI run with exit status, stdout and stderr, a run
// that must succeed, and the checks of a run that fails with one line and of a usage error.
#include <sys/wait.h>
#include <unistd.h>
#include "test_paths.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <system_error>

namespace rayint::test {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The number of lines of `s` (its newline characters).
inline long line_count(const std::string& s) {
  return static_cast<long>(std::count(s.begin(), s.end(), '\n'));
}

// A scratch directory under the system temp dir, removed on destruction.
struct TempDir {
  fs::path path;
  TempDir() {
    static int counter = 0;
    path = fs::temp_directory_path() /
           ("rayint-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
  }
  // Copies cases/<name>.json of the source tree into the folder.
  void copy_case(const std::string& name) const {
    fs::copy_file(fs::path(RAYINT_SOURCE_DIR) / "cases" / (name + ".json"), path / (name + ".json"));
  }
  std::set<std::string> entries() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(path)) names.insert(e.path().filename().string());
    return names;
  }
};

struct CliRun {
  int status = -1;  // exit status, or 128 + signal
  std::string out, err;
};

// Runs the real rayint binary with `args` (shell syntax) in `dir`; stdout and stderr are captured
// outside `dir`, so that `dir` shows exactly what rayint left there.
inline CliRun run_cli(const fs::path& dir, const std::string& args) {
  const fs::path out = dir.parent_path() / (dir.filename().string() + ".stdout");
  const fs::path err = dir.parent_path() / (dir.filename().string() + ".stderr");
  const std::string cmd = "cd '" + dir.string() + "' && '" + RAYINT_CLI_PATH + "' " + args + " >'" +
                          out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

// run_cli that must succeed: the test stops, showing the command and its stderr, unless it exits 0.
inline CliRun run_cli_ok(const fs::path& dir, const std::string& args) {
  CliRun r = run_cli(dir, args);
  INFO("rayint " << args << "\nstderr: " << r.err);
  REQUIRE(r.status == 0);
  return r;
}

// How rayint fails on bad input or a failed write: exit 2 and one line on stderr.
inline void check_one_line_exit(const CliRun& r) {
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(line_count(r.err) == 1);
}

// A command line refused as a usage error: exit 2, nothing on stdout, one stderr line starting
// "rayint: error: ".
inline void check_usage_error(const CliRun& r) {
  check_one_line_exit(r);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("rayint: error: ", 0) == 0);
}

}  // namespace rayint::test
