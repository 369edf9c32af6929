// Drift baselines (studies/drift.hpp, `rayint gate --baseline/--write-baseline`) and the
// accuracy limits of cases/gates.json against a method ten times worse.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/studies/drift.hpp"

namespace {

using namespace rayint;
using namespace rayint::test;

const std::string kSource = RAYINT_SOURCE_DIR;

std::string case_path(const std::string& name) { return kSource + "/cases/" + name + ".json"; }

// Moves the first number of the first ray of `method`'s baseline file in `dir` by `ulps`.
void nudge_baseline(const fs::path& file, int ulps) {
  auto j = nlohmann::json::parse(slurp(file));
  auto& v = j["cases"].begin().value()[0][0];
  double x = v.get<double>();
  for (int i = 0; i < ulps; ++i) x = std::nextafter(x, INFINITY);
  v = x;
  std::ofstream(file) << j.dump(2);
}

}  // namespace

TEST_CASE("ulp distance: neighbours, signed zeros, subnormals, non-finite", "[drift]") {
  CHECK(ulp_distance(1.0, std::nextafter(1.0, 2.0)) == 1.0);
  CHECK(ulp_distance(1.0, 1.0) == 0.0);
  CHECK(ulp_distance(0.0, -0.0) == 0.0);
  const double tiny = std::numeric_limits<double>::denorm_min();
  CHECK(ulp_distance(tiny, 0.0) == 1.0);
  CHECK(ulp_distance(-tiny, tiny) == 2.0);
  CHECK(ulp_distance(2.0, 1.0) == std::ldexp(1.0, 52));  // one binade: 2^52 doubles
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = INFINITY;
  CHECK(ulp_distance(nan, nan) == 0.0);
  CHECK(std::isinf(ulp_distance(nan, 1.0)));
  CHECK(ulp_distance(inf, inf) == 0.0);
  CHECK(std::isinf(ulp_distance(inf, -inf)));
  CHECK(std::isinf(ulp_distance(inf, 1.0)));
}

TEST_CASE("CLI: gate --write-baseline then --baseline: 0 ulps, 1 ulp within 4 passes, 5 ulps fail", "[drift]") {
  TempDir dir;
  fs::create_directories(dir.path / "base");
  dir.write("gates.json", R"({"corpus": {"cases": [")" + case_path("paper-figure-2") + R"(", ")" +
                              case_path("smooth-convergence") + R"("], "methods": {
      "exact": {"max_rel_error": 1e-13}, "riemann:n=64": {"max_rel_error": 1}}}})");
  const auto w = run_cli(dir.path, "gate --config gates.json --write-baseline base --quiet");
  INFO(w.err);
  REQUIRE(w.status == 0);
  const fs::path riemann = dir.path / "base" / "riemann_n_64.json";
  REQUIRE(fs::exists(riemann));
  REQUIRE(fs::exists(dir.path / "base" / "exact.json"));
  const std::string text = slurp(riemann);
  CHECK(text.find("do not edit") != std::string::npos);
  CHECK(text.find("rayint gate --config gates.json --write-baseline base") != std::string::npos);

  auto drift_of = [&](const std::string& extra) {
    const auto r = run_cli(dir.path, "gate --config gates.json --baseline base --json --quiet " + extra);
    INFO(r.err);
    const auto j = nlohmann::json::parse(r.out);
    for (const auto& c : j["checks"])
      if (c["name"] == "drift.riemann:n=64.max_ulp_drift") return std::make_pair(r.status, c);
    FAIL("no drift check");
    return std::make_pair(r.status, nlohmann::json());
  };
  auto [s0, c0] = drift_of("");
  CHECK(s0 == 0);
  CHECK(c0["measured"] == 0.0);
  CHECK(c0["limit"] == 4.0);
  nudge_baseline(riemann, 1);
  auto [s1, c1] = drift_of("");
  CHECK(s1 == 0);
  CHECK(c1["measured"] == 1.0);
  nudge_baseline(riemann, 4);  // 5 ulps in all
  auto [s5, c5] = drift_of("--junit j.xml");
  CHECK(s5 == 1);
  CHECK(c5["measured"] == 5.0);
  CHECK(c5["pass"] == false);
  const std::string junit = slurp(dir.path / "j.xml");
  CHECK(junit.find("name=\"drift.riemann:n=64.max_ulp_drift\"") != std::string::npos);
  CHECK(junit.find("measured 5, limit 4, factor 1.25") != std::string::npos);
  // A stricter allowance, and a missing baseline, fail.
  CHECK(drift_of("--drift-ulps 4.5").first == 1);
  CHECK(drift_of("--drift-ulps 5").first == 0);
  fs::remove(dir.path / "base" / "exact.json");
  const auto missing = run_cli(dir.path, "gate --config gates.json --baseline base --quiet");
  CHECK(missing.status == 1);
  CHECK(missing.out.find("FAIL drift.exact.max_ulp_drift") != std::string::npos);
}

TEST_CASE("CLI: gate on a user's own candidate files catches a moved number", "[drift]") {
  TempDir dir;
  fs::create_directories(dir.path / "base");
  dir.write("a.json", R"({"case": "paper-figure-2", "rays": [{"intensity": [0.5, 0.25, 0.125]},
      {"intensity": [0.1, 0.2, 0.3]}, {"intensity": [1, 2, 3]}]})");
  const auto w = run_cli(dir.path, "gate --candidate a.json --write-baseline base");
  INFO(w.err);
  REQUIRE(w.status == 0);
  REQUIRE(fs::exists(dir.path / "base" / "candidates.json"));
  CHECK(run_cli(dir.path, "gate --candidate a.json --baseline base").status == 0);
  dir.write("a.json", R"({"case": "paper-figure-2", "rays": [{"intensity": [0.5, 0.25, 0.125]},
      {"intensity": [0.1, 0.2000000001, 0.3]}, {"intensity": [1, 2, 3]}]})");
  const auto r = run_cli(dir.path, "gate --candidate a.json --baseline base");
  CHECK(r.status == 1);
  CHECK(r.out.find("FAIL drift.candidates.max_ulp_drift") != std::string::npos);
  CHECK(r.out.find("case paper-figure-2 ray 1 channel g") != std::string::npos);
  CHECK(run_cli(dir.path, "gate --candidate a.json").status == 2);  // needs a baseline option
}

TEST_CASE("cases/gates.json: a method ten times worse than riemann:n=64 fails its limits", "[drift]") {
  // riemann is second order on smooth rays, so n = 20 has (64/20)^2 = 10.2 times the error of
  // n = 64. Every limit set of riemann:n=64 in the committed config, applied to n = 20, must fail
  // at least one check; applied to n = 64 itself, all pass.
  const auto config = nlohmann::json::parse(slurp(fs::path(kSource) / "cases" / "gates.json"));
  const auto& sets = config["corpus"]["methods"]["riemann:n=64"];
  REQUIRE(sets.is_array());
  TempDir dir;
  for (const std::string n : {"64", "20"}) {
    nlohmann::json cases = nlohmann::json::array();
    for (const auto& set : sets)
      if (set.contains("cases"))
        for (const auto& c : set["cases"]) cases.push_back(case_path(c.get<std::string>()));
    nlohmann::json cfg;
    cfg["corpus"]["cases"] = cases;
    nlohmann::json limits = nlohmann::json::array();
    for (auto set : sets)
      if (set.contains("cases")) limits.push_back(set);
    cfg["corpus"]["methods"]["riemann:n=" + n] = limits;
    dir.write("g" + n + ".json", cfg.dump());
    const auto r = run_cli(dir.path, "gate --config g" + n + ".json --quiet");
    INFO(n << "\n" << r.out << r.err);
    CHECK(r.status == (n == "64" ? 0 : 1));
  }
}
