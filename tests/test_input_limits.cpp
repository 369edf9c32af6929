// Inputs that would cost without bound are refused with one line naming the file and the limit
// (issue 30, "Resource limits"; docs/limits.md): JSON nested deeper than kMaxJsonDepth, a file
// larger than the input limit (RAYINT_MAX_INPUT_BYTES), a device such as /dev/zero; a FIFO
// (/dev/stdin on a pipe) is read as a stream.
#include <catch2/catch.hpp>
#include <string>

#include "cli_harness.hpp"
#include "rayint/input/json_source.hpp"

using rayint::test::CliRun;
using rayint::test::line_count;
using rayint::test::run_cli;
using rayint::test::TempDir;

TEST_CASE("JSON nested deeper than the limit is refused at the limit, not before",
          "[reliability][input-limits]") {
  const std::size_t d = rayint::json_source::kMaxJsonDepth;
  const std::string ok = std::string(d, '[') + std::string(d, ']');
  CHECK_NOTHROW(rayint::json_source::parse(ok, "ok.json"));
  const std::string deep = std::string(d + 1, '[') + std::string(d + 1, ']');
  CHECK_THROWS_WITH(rayint::json_source::parse(deep, "deep.json"),
                    "deep.json: (root): nested deeper than 256 levels (the limit)");
}

TEST_CASE("The CLI refuses devices, oversized and over-nested inputs with one line",
          "[reliability][input-limits]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  dir.write("deep.json", std::string(100000, '[') + std::string(100000, ']'));
  const struct {
    std::string args, line;
  } refusals[] = {
      {"eval /dev/zero", "rayint: error: /dev/zero: cannot read file (is a device, not an input file)\n"},
      {"eval deep.json", "rayint: error: deep.json: (root): nested deeper than 256 levels (the limit)\n"},
  };
  for (const auto& r : refusals) {
    const CliRun run = run_cli(dir.path, r.args + " -o out.json");
    INFO(r.args);
    CHECK(run.status == 2);
    CHECK(run.err == r.line);
    CHECK_FALSE(rayint::test::fs::exists(dir.path / "out.json"));
  }
  const std::size_t size = rayint::test::fs::file_size(dir.path / "paper-figure-2.json");
  const std::string env = "RAYINT_MAX_INPUT_BYTES=" + std::to_string(size - 1);
  const std::string cmd = "cd '" + dir.path.string() + "' && " + env + " '" RAYINT_CLI_PATH
                          "' eval paper-figure-2.json -o out.json 2>err.txt; echo $? > rc.txt";
  REQUIRE(std::system(cmd.c_str()) == 0);
  CHECK(rayint::test::slurp(dir.path / "rc.txt") == "2\n");
  CHECK(rayint::test::slurp(dir.path / "err.txt") ==
        "rayint: error: paper-figure-2.json: cannot read file (larger than the input limit of " +
            std::to_string(size - 1) + " bytes; RAYINT_MAX_INPUT_BYTES raises it)\n");
  CHECK_FALSE(rayint::test::fs::exists(dir.path / "out.json"));
}

TEST_CASE("A case on standard input through a pipe is read as a stream", "[reliability][input-limits]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  const std::string cmd = "cd '" + dir.path.string() + "' && cat paper-figure-2.json | '" RAYINT_CLI_PATH
                          "' eval /dev/stdin --methods exact --no-timing >out.txt 2>err.txt; echo $? > rc.txt";
  REQUIRE(std::system(cmd.c_str()) == 0);
  INFO(rayint::test::slurp(dir.path / "err.txt"));
  CHECK(rayint::test::slurp(dir.path / "rc.txt") == "0\n");
  CHECK(rayint::test::slurp(dir.path / "out.txt").find("\"paper-figure-2\"") != std::string::npos);
}
