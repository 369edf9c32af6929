// `rayint eval` through the real binary (RAYINT_CLI_PATH): --no-reference leaves out the reference
// and the error fields (absent, not zero) and gives the same intensities; progress lines go to
// stderr only, and --quiet silences them.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "input_text.hpp"

namespace {

using rayint::test::CliRun;
using rayint::test::run_cli;
using rayint::test::TempDir;

const std::string kCase = rayint::test::fig2_case_text(R"([
    {"background": [0.0, 0.0, 0.0],
     "segments": [{"length": 1.0, "scalar": [0.1, 0.9]}, {"length": 0.25, "scalar": [0.9, 0.4]}]},
    {"segments": [{"length": 2.0, "scalar": [1.0, 0.0]}]}
  ])");

}  // namespace

TEST_CASE("CLI: eval --no-reference leaves out the reference and the error fields", "[cli][eval]") {
  const TempDir dir;
  dir.write("fig2.json", kCase);
  const CliRun with = run_cli(dir.path, "eval fig2.json --methods exact,paper --no-timing");
  const CliRun without =
      run_cli(dir.path, "eval fig2.json --methods exact,paper --no-timing --no-reference");
  REQUIRE(with.status == 0);
  REQUIRE(without.status == 0);
  const auto a = nlohmann::json::parse(with.out)["cases"][0];
  const auto b = nlohmann::json::parse(without.out)["cases"][0];
  CHECK_FALSE(a.contains("reference"));
  CHECK(b["reference"] == "skipped");
  REQUIRE(b["rays"].size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    INFO("ray " << i);
    CHECK(a["rays"][i].contains("reference"));
    CHECK_FALSE(b["rays"][i].contains("reference"));
    for (const char* m : {"exact", "paper"}) {
      INFO("method " << m);
      const auto& ma = a["rays"][i]["methods"][m];
      const auto& mb = b["rays"][i]["methods"][m];
      for (const char* f : {"abs_error", "rel_error", "ulp_error", "transmittance_rel_error"}) {
        CHECK(ma.contains(f));
        CHECK_FALSE(mb.contains(f));
      }
      CHECK(mb["intensity"] == ma["intensity"]);
      CHECK(mb["transmittance"] == ma["transmittance"]);
      CHECK(mb["finite"] == true);
    }
  }
  const CliRun table =
      run_cli(dir.path, "eval fig2.json --methods exact --no-timing --no-reference --format table");
  REQUIRE(table.status == 0);
  CHECK(table.out.find("skipped") != std::string::npos);
}

TEST_CASE("CLI: eval progress goes to stderr, never stdout, and --quiet silences it",
          "[cli][eval]") {
  const TempDir dir;
  dir.write("fig2.json", kCase);
  // --progress-every 0: a line at every step (the default, 1 s, prints nothing on a case this
  // small).
  const CliRun r = run_cli(dir.path, "eval fig2.json --methods exact --no-timing --progress-every 0");
  REQUIRE(r.status == 0);
  INFO("stderr: " << r.err);
  CHECK(r.err.find("eval: read 1 case file, 0 s\n") != std::string::npos);  // after reading, not per file
  CHECK(r.err.find("eval fig2: reference 3/3 segments (100%)") != std::string::npos);
  CHECK(r.err.find("eval fig2: method exact, ray 1/2") != std::string::npos);
  CHECK(r.err.find("eval fig2: method exact, ray 2/2") != std::string::npos);
  CHECK(r.out.find("eval ") == std::string::npos);
  CHECK(nlohmann::json::parse(r.out)["cases"][0]["rays"].size() == 2);  // stdout is the JSON only

  const CliRun quiet =
      run_cli(dir.path, "eval fig2.json --methods exact --no-timing --progress-every 0 --quiet");
  REQUIRE(quiet.status == 0);
  CHECK(quiet.err.empty());
  CHECK(quiet.out == r.out);
}
