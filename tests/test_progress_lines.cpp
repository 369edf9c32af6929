// cli/progress.hpp: a slow stage's lines wait until the input is accepted, so a bad input's
// error is the only line on stderr however long the reading took (issue 30, "one line, once").
// stderr is redirected to a file here (not a terminal: the log form of the lines).
#include <fcntl.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>

#include "../cli/progress.hpp"
#include "cli_harness.hpp"

namespace {

// Runs `body` with stderr (fd 2) written to a file; returns what it wrote.
template <class Body>
std::string stderr_of(Body body) {
  rayint::test::TempDir dir;
  const std::string path = (dir.path / "stderr.txt").string();
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  REQUIRE(saved >= 0);
  REQUIRE(fd >= 0);
  ::dup2(fd, STDERR_FILENO);
  ::close(fd);
  body();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  return rayint::test::slurp(path);
}

void slow_read(bool succeed) {
  rayint::cli::SlowStage reading("rayint render: reading the mesh of m.json", false);
  std::this_thread::sleep_for(std::chrono::milliseconds(1150));
  if (!succeed) throw std::runtime_error("bad field");
  reading.done("12 tets, 8 points");
}

}  // namespace

TEST_CASE("A slow stage that fails writes nothing, so the error is the only line", "[cli][progress]") {
  INFO("run with stderr not a terminal (as ctest does): this checks the log form of the lines");
  REQUIRE_FALSE(rayint::cli::stderr_is_terminal());
  const std::string err = stderr_of([] {
    CHECK_THROWS_AS(slow_read(false), std::runtime_error);
  });
  CHECK(err.empty());
}

TEST_CASE("A slow stage's line is held until the computation starts", "[cli][progress]") {
  const std::string before = stderr_of([] { slow_read(true); });
  CHECK(before.empty());  // held: a later check of the input may still fail
  const std::string after = stderr_of([] {
    rayint::cli::ProgressLine progress;
    progress.update("rayint render: 1/4 rows", 0.25);
  });
  CHECK(after.rfind("rayint render: reading the mesh of m.json: 12 tets, 8 points (1.", 0) == 0);
  CHECK(after.find(" s)\nrayint render: 1/4 rows\n") != std::string::npos);
  CHECK(rayint::test::line_count(after) == 2);
  // Released once: the next update prints only itself.
  const std::string again = stderr_of([] {
    rayint::cli::ProgressLine progress;
    progress.update("rayint render: 4/4 rows", 1.0);
  });
  CHECK(again == "rayint render: 4/4 rows\n");
}

TEST_CASE("A stage that ends within a second holds nothing", "[cli][progress]") {
  const std::string err = stderr_of([] {
    {
      rayint::cli::SlowStage quick("rayint render: building the traversal", false);
      quick.done("6 faces");
    }
    rayint::cli::HeldLines::instance().release();
  });
  CHECK(err.empty());
}
