// Bad input to the real rayint binary (RAYINT_CLI_PATH), one test per class of malformed input:
// each runs `rayint eval` and `rayint check` (and, for candidate files, `check` alone) with
// `--output out.json` in a scratch directory and requires
//   - exit status 2 (not 1, not a crash),
//   - nothing on stdout and exactly one line on stderr,
//     `rayint: error: <file>: <field path>: <what>`, naming the file and the field,
//   - no output file left behind, not even a temporary one: the directory holds exactly the
//     input files it held before.
// The messages themselves are tested in test_case_reader.cpp and test_check.cpp; this file
// tests what a user of the command line sees.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <string_view>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "input_text.hpp"

namespace fs = std::filesystem;

namespace {

// A valid case (Williams & Max Fig. 2, first interval) and a candidate that matches it; each test
// breaks one thing in one of them.
const std::string kCase = rayint::test::fig2_case_text(R"([
    {"background": [0.0, 0.0, 0.0],
     "segments": [{"length": 1.0, "scalar": [0.1, 0.9]}, {"length": 0.25, "scalar": [0.9, 0.4]}]},
    {"segments": [{"length": 2.0, "scalar": [1.0, 0.0]}]}
  ])");

const std::string kCandidate = R"({
  "case": "fig2",
  "renderer": "test",
  "rays": [{"intensity": [1.0, 0.5, 0.1]}, {"intensity": [1.5, 0.9, 0.2]}]
})";

// kCase, kCandidate with the first occurrence of `from` replaced by `to` (which must exist).
std::string case_with(std::string_view from, std::string_view to) {
  return rayint::test::replace_first(kCase, from, to);
}
std::string candidate_with(std::string_view from, std::string_view to) {
  return rayint::test::replace_first(kCandidate, from, to);
}

using rayint::test::CliRun;
using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;

// Runs `args --output out.json` in `dir` and checks everything a bad input must give: exit 2,
// no stdout, one stderr line starting `rayint: error: <prefix>` and containing `what`, and the
// directory unchanged.
void expect_bad_input(const TempDir& dir, const std::string& args, const std::string& prefix,
                      const std::string& what) {
  const std::set<std::string> before = dir.entries();
  const CliRun r = run_cli(dir.path, args + " --output out.json");
  INFO("rayint " << args << "\nexit status " << r.status << "\nstderr: " << r.err
                 << "\nstdout: " << r.out);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK((!r.err.empty() && r.err.back() == '\n'));
  CHECK(r.err.rfind("rayint: error: " + prefix, 0) == 0);
  CHECK(r.err.find(what) != std::string::npos);
  CHECK(dir.entries() == before);  // no out.json, no out.json.tmp.<pid>
}

// A broken case file, through `eval` and through `check` (with a valid candidate). The message
// must name the file and the field: `bad-case.json: <field>: <what>`.
void expect_bad_case(const std::string& case_text, const std::string& field,
                     const std::string& what) {
  const TempDir dir;
  dir.write("bad-case.json", case_text);
  dir.write("candidate.json", kCandidate);
  const std::string prefix = "bad-case.json: " + field + ": ";
  expect_bad_input(dir, "eval bad-case.json", prefix, what);
  expect_bad_input(dir, "check bad-case.json --candidate candidate.json", prefix, what);
}

// A broken candidate for a valid case: `bad-candidate.json: <field>: <what>`.
void expect_bad_candidate(const std::string& candidate_text, const std::string& field,
                          const std::string& what) {
  const TempDir dir;
  dir.write("case.json", kCase);
  dir.write("bad-candidate.json", candidate_text);
  expect_bad_input(dir, "check case.json --candidate bad-candidate.json",
                   "bad-candidate.json: " + field + ": ", what);
}

}  // namespace

TEST_CASE("the valid inputs of these tests are accepted", "[cli][bad_input]") {
  const TempDir dir;
  dir.write("case.json", kCase);
  dir.write("candidate.json", kCandidate);
  const CliRun eval = run_cli(dir.path, "eval case.json --no-timing --output out.json");
  CHECK(eval.status == 0);
  CHECK(eval.err.empty());
  CHECK(fs::exists(dir.path / "out.json"));
  // The candidate's numbers are not the exact ones: a well-formed candidate fails with 1, not 2.
  const CliRun check = run_cli(dir.path, "check case.json --candidate candidate.json -o diff.json");
  CHECK(check.status == 1);
  CHECK(fs::exists(dir.path / "diff.json"));
}

TEST_CASE("bad input: invalid JSON", "[cli][bad_input]") {
  expect_bad_case(case_with(R"("name": "fig2",)", R"("name": "fig2",,)"), "(root)",
                  "invalid JSON at line 2, column 18");
  expect_bad_case("", "(root)", "invalid JSON at line 1, column 1");
  expect_bad_case(kCase.substr(0, kCase.size() / 2), "(root)", "invalid JSON");
  expect_bad_case(kCase + "\n}", "(root)", "invalid JSON at line 13, column 1");
  expect_bad_candidate(candidate_with(R"("renderer": "test",)", R"("renderer": "test" )"), "(root)",
                       "invalid JSON at line 4");
  expect_bad_candidate("\x01\x02", "(root)", "invalid JSON at line 1, column 1");

  // With several case files, a bad one anywhere means no report at all.
  const TempDir dir;
  dir.write("good.json", kCase);
  dir.write("bad-case.json", "{");
  expect_bad_input(dir, "eval good.json bad-case.json", "bad-case.json: (root): ", "invalid JSON");
  // ... and so does a bad one in a folder given to `eval`, named with its folder.
  fs::create_directory(dir.path / "folder");
  std::ofstream(dir.path / "folder" / "a-good.json") << kCase;
  std::ofstream(dir.path / "folder" / "b-bad.json") << kCase.substr(0, 20);
  expect_bad_input(dir, "eval folder", "folder/b-bad.json: (root): ", "invalid JSON");
  // Progress due after every file (as when reading is slow): still the error line alone, since
  // every file is read before anything else is printed.
  expect_bad_input(dir, "eval folder --progress-every 0", "folder/b-bad.json: (root): ", "invalid JSON");
}

TEST_CASE("bad input: wrong types", "[cli][bad_input]") {
  expect_bad_case(case_with(R"("length": 2.0)", R"("length": "2")"), "rays[1].segments[0].length",
                  "must be a number, got string");
  expect_bad_case(case_with(R"("name": "fig2")", R"("name": 7)"), "name",
                  "must be a non-empty string, got number");
  expect_bad_case("[]", "(root)", "must be an object, got array");
  expect_bad_candidate(candidate_with("[1.0, 0.5, 0.1]", R"("white")"), "rays[0].intensity",
                       "must be an array of 3 numbers [r, g, b], got string");
  expect_bad_candidate(candidate_with("[1.5, 0.9, 0.2]", "[1.5, true, 0.2]"),
                       "rays[1].intensity[1]", "must be a finite number, got boolean");
}

TEST_CASE("bad input: missing fields", "[cli][bad_input]") {
  expect_bad_case(case_with(R"("name": "fig2",)", ""), "name", "missing required field");
  expect_bad_case(case_with(R"({"length": 2.0, "scalar": [1.0, 0.0]})", R"({"length": 2.0})"),
                  "rays[1].segments[0].scalar", "missing required field");
  expect_bad_candidate(candidate_with(R"("case": "fig2",)", ""), "case", "missing required field");
  expect_bad_candidate(candidate_with(R"({"intensity": [1.5, 0.9, 0.2]})", "{}"),
                       "rays[1].intensity", "missing required field");
}

TEST_CASE("bad input: unknown fields", "[cli][bad_input]") {
  expect_bad_case(case_with(R"("rays")", R"("ray")"), "ray", "unknown field");
  expect_bad_case(case_with(R"("g": [[0.0, 1.0]])", R"("green": [[0.0, 1.0]])"),
                  "transfer_function.color.green", "unknown field (expected r, g, b)");
  expect_bad_candidate(candidate_with(R"({"intensity": [1.0, 0.5, 0.1]})",
                                      R"({"intensity": [1.0, 0.5, 0.1], "alpha": 1})"),
                       "rays[0].alpha", "unknown field (expected index, intensity)");
}

TEST_CASE("bad input: NaN and Inf", "[cli][bad_input]") {
  // JSON has no NaN/Inf literals: a number that overflows a double is the way to write one.
  expect_bad_case(
      case_with(R"("background": [0.0, 0.0, 0.0])", R"("background": [0.0, 1e999, 0.0])"),
      "rays[0].background[1]", "must be finite, got 1e999");
  expect_bad_case(case_with(R"("scalar": [1.0, 0.0])", R"("scalar": [1.0, -1e400])"),
                  "rays[1].segments[0].scalar[1]", "must be finite");
  expect_bad_case(case_with(R"("length": 2.0)", R"("length": NaN)"), "(root)", "invalid JSON");
  expect_bad_candidate(candidate_with("[1.5, 0.9, 0.2]", "[1.5, 0.9, 1e999]"),
                       "rays[1].intensity[2]", "must be finite, got 1e999");
  expect_bad_candidate(candidate_with("[1.0, 0.5, 0.1]", "[null, 0.5, 0.1]"),
                       "rays[0].intensity[0]", "got null (JSON has no NaN or Inf)");
  expect_bad_candidate(candidate_with("[1.0, 0.5, 0.1]", "[Infinity, 0.5, 0.1]"), "(root)",
                       "invalid JSON");
}

TEST_CASE("bad input: negative values", "[cli][bad_input]") {
  expect_bad_case(case_with("[1.0, 2.0]]", "[1.0, -2.0]]"), "transfer_function.density[1][1]",
                  "must be finite and >= 0, got -2");
  expect_bad_case(case_with(R"("b": [[0.0, 0.2]])", R"("b": [[0.0, -0.2]])"),
                  "transfer_function.color.b[0][1]", "must be finite and >= 0, got -0.2");
  expect_bad_case(case_with(R"("background": [0.0, 0.0, 0.0])", R"("background": [0.0, 0.0, -1])"),
                  "rays[0].background[2]", "must be finite and >= 0, got -1");
}

TEST_CASE("bad input: non-increasing breakpoints", "[cli][bad_input]") {
  expect_bad_case(case_with("[[0.0, 5.0], [1.0, 2.0]]", "[[0.0, 5.0], [0.0, 2.0], [0.0, 1.0]]"),
                  "transfer_function.density[2][0]", "scalar 0 appears three times");
  expect_bad_case(case_with(R"("r": [[0.0, 1.7]])", R"("r": [[1.0, 1.7], [0.5, 1.0]])"),
                  "transfer_function.color.r[1][0]", "non-decreasing (0.5 after 1)");
}

TEST_CASE("bad input: empty rays", "[cli][bad_input]") {
  const std::string no_rays = kCase.substr(0, kCase.find(R"("rays")")) + R"("rays": []})";
  expect_bad_case(no_rays, "rays", "must be a non-empty array");
  expect_bad_case(
      case_with(R"("segments": [{"length": 2.0, "scalar": [1.0, 0.0]}])", R"("segments": [])"),
      "rays[1].segments", "must be a non-empty array");
  expect_bad_case(case_with(R"("density": [[0.0, 5.0], [1.0, 2.0]])", R"("density": [])"),
                  "transfer_function.density", "must be a non-empty array");
  expect_bad_candidate(R"({"case": "fig2", "rays": []})", "rays", "must be a non-empty array");
}

TEST_CASE("bad input: negative lengths", "[cli][bad_input]") {
  expect_bad_case(case_with(R"("length": 0.25)", R"("length": -0.25)"),
                  "rays[0].segments[1].length", "must be finite and >= 0, got -0.25");
}

TEST_CASE("bad input: unreadable files", "[cli][bad_input]") {
  const TempDir dir;
  dir.write("case.json", kCase);
  dir.write("candidate.json", kCandidate);
  fs::create_directory(dir.path / "a-directory.json");
  for (const std::string sub :
       {"eval missing.json", "check missing.json --candidate candidate.json"})
    expect_bad_input(dir, sub, "missing.json: ", "cannot read file (No such file or directory)");
  // `check` takes one case file; (`eval` also takes a folder of cases, tested below).
  expect_bad_input(dir, "check a-directory.json --candidate candidate.json",
                   "a-directory.json: ", "cannot read file");
  expect_bad_input(dir, "check case.json --candidate missing.json",
                   "missing.json: ", "cannot read file (No such file or directory)");
  expect_bad_input(dir, "check case.json --candidate a-directory.json",
                   "a-directory.json: ", "cannot read file");
}

TEST_CASE("bad input: a candidate that does not match the case", "[cli][bad_input]") {
  expect_bad_candidate(candidate_with(R"("case": "fig2")", R"("case": "fig3")"), "case",
                       R"(is "fig3" but the case file case.json is named "fig2")");
  expect_bad_candidate(candidate_with(R"(, {"intensity": [1.5, 0.9, 0.2]})", ""), "rays",
                       "has 1 entries but the case file case.json has 2 rays");
  expect_bad_candidate(
      candidate_with(R"({"intensity": [1.5, 0.9, 0.2]})",
                     R"({"intensity": [1.5, 0.9, 0.2]}, {"intensity": [0, 0, 0]})"),
      "rays", "has 3 entries but the case file case.json has 2 rays");
  expect_bad_candidate(candidate_with("[1.5, 0.9, 0.2]", "[1.5, 0.9, 0.2, 1.0]"),
                       "rays[1].intensity", "got an array of 4");
  expect_bad_candidate(candidate_with("[1.0, 0.5, 0.1]", "[0.7]"), "rays[0].intensity",
                       "got an array of 1");
  expect_bad_candidate(candidate_with(R"({"intensity": [1.5, 0.9, 0.2]})",
                                      R"({"index": 0, "intensity": [1.5, 0.9, 0.2]})"),
                       "rays[1].index", "must be 1");
}

TEST_CASE("bad input: invalid options and an unwritable output", "[cli][bad_input]") {
  const TempDir dir;
  dir.write("case.json", kCase);
  dir.write("candidate.json", kCandidate);
  expect_bad_input(dir, "check case.json", "--candidate", "required");
  expect_bad_input(dir, "check case.json --candidate candidate.json --rel-tol -1",
                   "--rel-tol: ", "must be a finite number >= 0, got -1");
  expect_bad_input(dir, "check case.json --candidate candidate.json --abs-tol nan",
                   "--abs-tol: ", "must be a finite number >= 0, got nan");
  // The output goes through a temporary file and a rename: a failure leaves neither behind.
  for (const std::string sub :
       {"eval case.json --no-timing", "check case.json --candidate candidate.json"}) {
    const std::set<std::string> before = dir.entries();
    const CliRun r = run_cli(dir.path, sub + " --output no-such-dir/out.json");
    INFO("rayint " << sub << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.rfind("rayint: error: no-such-dir/out.json: cannot write file", 0) == 0);
    CHECK(dir.entries() == before);
  }
}
