// Outputs that are never lost or half-written (issue 30, "Outputs"): links are followed,
// FIFOs and devices are streamed into and never replaced, a failed write (a full disk, a full
// stdout) is an error with one line, a command's outputs land together or not at all, and a
// signal leaves no temporary file behind. The CLI cases run the real binary (RAYINT_CLI_PATH).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/core/atomic_file.hpp"

namespace fs = std::filesystem;
using rayint::test::check_one_line_exit;
using rayint::test::CliRun;
using rayint::test::line_count;
using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;

namespace {

bool is_temporary(const std::string& name) { return name.find(".tmp.") != std::string::npos; }

// Runs `shell` (a whole command line, rayint's path in RAYINT) in `dir` with stderr captured;
// returns the exit status (128 + signal when killed).
CliRun run_shell(const fs::path& dir, const std::string& shell) {
  const fs::path err = dir.parent_path() / (dir.filename().string() + ".stderr");
  const std::string cmd = "cd '" + dir.string() + "' && RAYINT='" + RAYINT_CLI_PATH + "' && (" + shell +
                          ") 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  CliRun r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
  r.err = slurp(err);
  return r;
}

}  // namespace

TEST_CASE("An output through a symbolic link writes the link's target and keeps the link",
          "[reliability][outputs]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  fs::create_directory(dir.path / "real");
  fs::create_symlink("real/target.json", dir.path / "link.json");  // dangling until written
  const CliRun r = run_cli(dir.path, "eval paper-figure-2.json --no-timing -o link.json");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(fs::is_symlink(dir.path / "link.json"));
  CHECK(slurp(dir.path / "real" / "target.json").find("\"paper-figure-2\"") != std::string::npos);
  // A second run replaces the target's content, still through the link.
  const CliRun again = run_cli(dir.path, "eval paper-figure-2.json --no-timing --methods exact -o link.json");
  REQUIRE(again.status == 0);
  CHECK(fs::is_symlink(dir.path / "link.json"));
  CHECK(slurp(dir.path / "real" / "target.json").find("\"paper\"") == std::string::npos);
}

TEST_CASE("An output onto /dev/null or a FIFO streams into it and never replaces it",
          "[reliability][outputs]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  struct stat before {};
  REQUIRE(::stat("/dev/null", &before) == 0);
  REQUIRE(S_ISCHR(before.st_mode));
  const CliRun r = run_cli(dir.path, "eval paper-figure-2.json --no-timing -o /dev/null");
  CHECK(r.status == 0);
  struct stat after {};
  REQUIRE(::lstat("/dev/null", &after) == 0);
  CHECK(S_ISCHR(after.st_mode));
  CHECK(after.st_rdev == before.st_rdev);

  REQUIRE(::mkfifo((dir.path / "pipe").c_str(), 0600) == 0);
  const CliRun f = run_shell(dir.path,
                             "cat pipe > got.json & \"$RAYINT\" eval paper-figure-2.json --no-timing "
                             "-o pipe; s=$?; wait; exit $s");
  INFO(f.err);
  CHECK(f.status == 0);
  struct stat fifo {};
  REQUIRE(::lstat((dir.path / "pipe").c_str(), &fifo) == 0);
  CHECK(S_ISFIFO(fifo.st_mode));
  CHECK(slurp(dir.path / "got.json").find("\"paper-figure-2\"") != std::string::npos);
}

TEST_CASE("A directory as an output file is refused with one line", "[reliability][outputs]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  fs::create_directory(dir.path / "out.json");
  const CliRun r = run_cli(dir.path, "eval paper-figure-2.json --no-timing -o out.json");
  check_one_line_exit(r);
  CHECK(r.err == "rayint: error: out.json: is a directory, not an output file\n");
  CHECK(fs::is_directory(dir.path / "out.json"));
}

TEST_CASE("A failed write to standard output exits non-zero with one line",
          "[reliability][outputs]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  const CliRun r = run_shell(dir.path, "\"$RAYINT\" eval paper-figure-2.json --no-timing > /dev/full");
  check_one_line_exit(r);
  CHECK(r.err.find("standard output: cannot write (No space left on device)") != std::string::npos);
}

TEST_CASE("A full disk mid-run leaves every earlier output of the command as it was",
          "[reliability][outputs]") {
  const TempDir dir;
  const std::string mesh_case = "'" + RAYINT_SOURCE_DIR + "/cases/mesh-ball-radial.json'";
  dir.write("img.npy", "old image");
  dir.write("stats.json", "old stats");
  // ulimit -f 64 (64 KiB per file): the 128x128 RGB float image (196 KiB) cannot be written,
  // the statistics (a few KiB) can. SIGXFSZ ignored, so the write fails with EFBIG instead.
  const CliRun r = run_shell(dir.path,
                             "trap '' XFSZ; ulimit -f 64; \"$RAYINT\" render " + mesh_case +
                                 " -o img.npy --stats stats.json");
  INFO(r.err);
  CHECK(r.status == 2);  // (render's progress line may precede the error: issue 30, "one line")
  const std::string want = "rayint: error: img.npy: cannot write file (File too large)\n";
  REQUIRE(r.err.size() >= want.size());
  CHECK(r.err.compare(r.err.size() - want.size(), want.size(), want) == 0);
  CHECK(slurp(dir.path / "img.npy") == "old image");
  CHECK(slurp(dir.path / "stats.json") == "old stats");
  for (const auto& name : dir.entries()) CHECK_FALSE(is_temporary(name));
  // The same command with room for both writes both.
  const CliRun ok = run_shell(dir.path, "\"$RAYINT\" render " + mesh_case + " -o img.npy --stats stats.json");
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(slurp(dir.path / "stats.json") != "old stats");
  CHECK(fs::file_size(dir.path / "img.npy") > 128u * 128u * 3u * 4u);
}

TEST_CASE("OutputBatch renames on commit and removes its temporaries otherwise",
          "[reliability][outputs]") {
  const TempDir dir;
  const std::string a = (dir.path / "a.txt").string();
  const std::string b = (dir.path / "b.txt").string();
  dir.write("a.txt", "old a");
  {
    rayint::OutputBatch batch;
    rayint::write_file_atomically(a, "new a");
    rayint::write_file_atomically(b, "new b");
    CHECK(slurp(a) == "old a");  // staged, not yet visible
    CHECK(dir.entries().size() == 3);  // a.txt and two temporaries
  }  // destroyed without commit
  CHECK(slurp(a) == "old a");
  CHECK(dir.entries() == std::set<std::string>{"a.txt"});
  {
    rayint::OutputBatch batch;
    rayint::write_file_atomically(a, "new a");
    rayint::write_file_atomically(b, "new b");
    batch.commit();
  }
  CHECK(slurp(a) == "new a");
  CHECK(slurp(b) == "new b");
  CHECK(dir.entries() == std::set<std::string>{"a.txt", "b.txt"});
}

TEST_CASE("A signal during a command removes its temporary outputs", "[reliability][outputs]") {
  for (const int sig : {SIGINT, SIGTERM}) {
    const TempDir dir;
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {  // stage one output, say so, wait for the signal
      ::signal(sig, SIG_DFL);
      rayint::remove_temporaries_on_signals();
      rayint::OutputBatch batch;
      rayint::write_file_atomically((dir.path / "out.npy").string(), std::string(1000, 'x'));
      const char c = 'r';
      if (::write(ready[1], &c, 1) != 1) ::_exit(3);
      for (;;) ::pause();
    }
    ::close(ready[1]);
    char c = 0;
    REQUIRE(::read(ready[0], &c, 1) == 1);
    ::close(ready[0]);
    // The staged temporary exists now (so the check below can fail) ...
    const auto staged = dir.entries();
    REQUIRE(staged.size() == 1);
    CHECK(is_temporary(*staged.begin()));
    ::kill(child, sig);
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    // ... and the process ended by the signal, leaving nothing.
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK(dir.entries().empty());
  }
}
