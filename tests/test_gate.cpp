// `rayint gate` (src/rayint/studies/gate.hpp, input/gate_config.hpp, docs/gates.md): a config is
// read strictly (one line naming the file and the field for every problem, exit 2), paths are
// relative to the config, a limit that cannot hold fails with exit 1 and says by how much, and
// the project's own config (cases/gates.json) holds. CTest also runs the real command on that
// config in full (tests/CMakeLists.txt, test `gate`); here its stress sample is cut down.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "test_paths.hpp"
#include "rayint/studies/gate.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/gate_config.hpp"
#include "rayint/report/stress_json.hpp"
#include "cli_harness.hpp"

using namespace rayint;
namespace fs = std::filesystem;

using namespace rayint::test;  // the CLI harness

namespace {

// The message parse_gate_config_text throws for `text` (empty if it does not throw).
std::string config_error(const std::string& text, const std::string& source) {
  try {
    parse_gate_config_text(text, source);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("gate: a limit that cannot hold fails, exit 1, naming the check and by how much",
          "[gate]") {
  const TempDir dir;
  dir.copy_case("smooth-convergence");
  dir.copy_case("paper-figure-2");
  // One Riemann sample per segment is certainly inexact on a smooth, varying colour (measured
  // ~1.7e-2); exact holds its 1e-13 on the same cases.
  dir.write("gates.json", R"({
    "corpus": {
      "cases": ["*.json"],
      "methods": {
        "exact": {"max_rel_error": 1e-13, "max_non_finite": 0},
        "riemann:n=1": [{"max_rel_error": 0, "cases": ["smooth-convergence"]},
                        {"max_rel_error": 1e-6, "cases": ["smooth-convergence"]}]
      }
    }
  })");
  const CliRun r = run_cli(dir.path, "gate --config gates.json -q");
  CHECK(r.status == 1);
  CHECK(r.err.empty());
  INFO(r.out);
  CHECK(r.out.find("PASS corpus.paper-figure-2.exact.max_rel_error: measured") != std::string::npos);
  CHECK(r.out.find("PASS corpus.smooth-convergence.exact.max_non_finite: measured 0 (limit 0)") !=
        std::string::npos);
  CHECK(r.out.find("FAIL corpus.smooth-convergence.riemann:n=1.max_rel_error: measured 0.0") !=
        std::string::npos);
  CHECK(r.out.find("(limit 0)") != std::string::npos);
  CHECK(r.out.find("(limit 1e-06), ") != std::string::npos);  // "..., N times the limit"
  CHECK(r.out.find(" times the limit") != std::string::npos);
  CHECK(r.out.find("gate: 6 checks, 2 failed: FAIL") != std::string::npos);
  // gates.json itself matches *.json but is not a case.
  CHECK(r.out.find("corpus.gates") == std::string::npos);

  // The JSON form says the same.
  const CliRun j = run_cli(dir.path, "gate --config gates.json -q --json -o result.json");
  CHECK(j.status == 1);
  CHECK(j.out.empty());
  const auto result = nlohmann::json::parse(slurp(dir.path / "result.json"));
  CHECK(result["pass"] == false);
  CHECK(result["failures"] == 2);
  REQUIRE(result["checks"].size() == 6);
  for (const auto& c : result["checks"])
    CHECK(c["pass"] == (c["name"].get<std::string>().find("riemann") == std::string::npos));
}

TEST_CASE("gate: a method that fails or is non-finite fails its checks with the reason", "[gate]") {
  const TempDir dir;
  dir.copy_case("per-channel-densities");
  // The particle model needs a single transfer function; this case has per-channel densities.
  dir.write("gates.json", R"({"corpus": {"cases": ["per-channel-densities.json"],
    "methods": {"particle": {"max_rel_error": 1, "max_non_finite": 0}}}})");
  const CliRun r = run_cli(dir.path, "gate --config gates.json -q");
  CHECK(r.status == 1);
  INFO(r.out);
  CHECK(r.out.find("FAIL corpus.per-channel-densities.particle.max_rel_error: measured inf (limit 1)"
                   " -- ray 0: particle: needs a single transfer function") != std::string::npos);
  CHECK(r.out.find("FAIL corpus.per-channel-densities.particle.max_non_finite: measured") !=
        std::string::npos);
}

TEST_CASE("gate: the project's config is valid and holds (stress sample cut down here)", "[gate]") {
  GateConfig cfg = read_gate_config(RAYINT_SOURCE_DIR + "/cases/gates.json");
  // Paths are relative to the config: every case file of cases/, not the config itself.
  CHECK(cfg.case_files.size() >= 20);
  for (const auto& f : cfg.case_files) {
    CHECK(fs::path(f).parent_path() == fs::path(RAYINT_SOURCE_DIR + "/cases").lexically_normal());
    CHECK(fs::path(f).filename() != "gates.json");
  }
  // exact on the corpus: at least as strict as the issue's target (1e-13), with the underflow
  // rule; since issue 18 the limits sit within 2x of the measured error (1.5x, tighten-gates.py).
  const auto exact = std::find_if(cfg.corpus_methods.begin(), cfg.corpus_methods.end(),
                                  [](const GateMethod& m) { return m.spec.label() == "exact"; });
  REQUIRE(exact != cfg.corpus_methods.end());
  CHECK(exact->limits.at("max_rel_error") <= 1e-13);
  CHECK(exact->limits.at("max_abs_error_underflow") <= 1e-300);
  CHECK(exact->only.empty());
  REQUIRE(cfg.stress);
  CHECK(cfg.stress_regimes.empty());  // every regime
  CHECK(cfg.stress_count >= 15);

  cfg.stress_count = 1500;
  cfg.stress_regimes = {Regime::thin, Regime::thick, Regime::q2_near_zero_neg, Regime::steep_up,
                        Regime::narrow_pulse, Regime::out_of_range};
  const GateReport report = run_gate(cfg);
  for (const GateCheck& c : report.checks) {
    INFO(c.name << ": measured " << c.measured << " limit " << c.limit << " " << c.note);
    CHECK(c.pass);
  }
  CHECK(report.pass());
  CHECK(report.checks.size() > 100);
}

TEST_CASE("gate: config errors are one line naming the file and the field", "[gate]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  const std::string src = (dir.path / "g.json").string();
  auto error = [&](const std::string& text) { return config_error(text, src); };
  const std::string ok_methods = R"("methods": {"exact": {"max_rel_error": 1e-13}})";

  CHECK(error(R"({"corpus": {"cases": ["*.json"], )" + ok_methods + "}}").empty());
  CHECK(error("{").rfind(src + ": (root): invalid JSON at line 1, column 2: ", 0) == 0);
  CHECK(error("[]") == src + ": (root): must be an object, got array");
  CHECK(error("{}") == src + R"(: (root): needs a "corpus" or a "stress" section (or both))");
  CHECK(error(R"({"corpus": {}, "extra": 1})") ==
        src + ": extra: unknown field (expected corpus, stress)");
  CHECK(error(R"({"corpus": {"methods": {}}})") == src + ": corpus.cases: missing required field");
  CHECK(error(R"({"corpus": {"cases": [], )" + ok_methods + "}}") ==
        src + ": corpus.cases: must be a non-empty array of strings, got []");
  CHECK(error(R"({"corpus": {"cases": [""], )" + ok_methods + "}}") ==
        src + R"(: corpus.cases[0]: must be a non-empty string, got "")");
  CHECK(error(R"({"corpus": {"cases": ["nope.json"], )" + ok_methods + "}}") ==
        src + ": corpus.cases[0]: no such case file: " + (dir.path / "nope.json").string());
  CHECK(error(R"({"corpus": {"cases": ["*.nomatch"], )" + ok_methods + "}}") ==
        src + ": corpus.cases[0]: no file matches " + (dir.path / "*.nomatch").string());
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"nosuch": {"max_rel_error": 1}}}})")
            .rfind(src + ": corpus.methods.nosuch: unknown method 'nosuch'", 0) == 0);
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"riemann:n=abc": {"max_rel_error": 1}}}})")
            .rfind(src + ": corpus.methods.riemann:n=abc: ", 0) == 0);
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_eror": 1}}}})")
            .rfind(src + ": corpus.methods.exact.max_rel_eror: unknown field (expected max_rel_error, ", 0) == 0);
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_error": -1}}}})") ==
        src + ": corpus.methods.exact.max_rel_error: must be a finite number >= 0, got -1");
  // A number that overflows a double is named at its field, as in case files (json_source).
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_error": 1e999}}}})") ==
        src + ": corpus.methods.exact.max_rel_error: must be finite, got 1e999");
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_error": "1"}}}})") ==
        src + R"(: corpus.methods.exact.max_rel_error: must be a finite number >= 0, got "1")");
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"cases": ["paper-figure-2"]}}}})") ==
        src + ": corpus.methods.exact: sets no limit");
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_error": 1, "cases": ["medical-ct"]}}}})") ==
        src + ": corpus.methods.exact.cases[0]: 'medical-ct' is not one of the cases run here");
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": [{"max_rel_error": 1}, {"max_rel_eror": 1}]}}})")
            .rfind(src + ": corpus.methods.exact[1].max_rel_eror: unknown field", 0) == 0);
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": []}}})") ==
        src + ": corpus.methods.exact: must be a limit set or a non-empty array of them, got []");
  CHECK(error(R"({"corpus": {"cases": ["*.json"], "methods": {"exact": {"max_rel_error": 1, "max_rel_error": 0}}}})") ==
        src + ": corpus.methods.exact.max_rel_error: duplicate field");
  CHECK(error(R"({"stress": {"count": 10, "seed": 1, "methods": {"exact": {"max_rel_error": 1}}, "seed": 2}})") ==
        src + ": stress.seed: duplicate field");
  CHECK(error(R"({"stress": {"count": 0, "seed": 1, "methods": {"exact": {"max_rel_error": 1}}}})") ==
        src + ": stress.count: must be an integer >= 1, got 0");
  CHECK(error(R"({"stress": {"count": 10, "seed": -1, "methods": {"exact": {"max_rel_error": 1}}}})") ==
        src + ": stress.seed: must be an integer >= 0, got -1");
  CHECK(error(R"({"stress": {"count": 10, "seed": 1, "regimes": ["thin", "thik"], "methods": {"exact": {"max_rel_error": 1}}}})") ==
        src + ": stress.regimes[1]: unknown regime 'thik'");
  CHECK(error(R"({"stress": {"count": 10, "seed": 1, "regimes": ["thin"], "methods": {"exact": {"max_rel_error": 1, "regimes": ["thick"]}}}})") ==
        src + ": stress.methods.exact.regimes[0]: 'thick' is not one of the regimes run here");
  CHECK(error(R"({"stress": {"count": 10, "seed": 1}})") == src + ": stress.methods: missing required field");
}

TEST_CASE("gate: a bad config or option exits 2 with one line and nothing on stdout",
          "[gate][cli]") {
  const TempDir dir;
  dir.copy_case("paper-figure-2");
  dir.write("typo.json", R"({"corpus": {"cases": ["paper-figure-2.json"],
    "methods": {"exact": {"max_rel_eror": 1e-13}}}})");
  dir.write("broken.json", R"({"corpus": )");
  for (const auto& [args, field] : std::vector<std::pair<std::string, std::string>>{
           {"gate --config typo.json", "typo.json: corpus.methods.exact.max_rel_eror: unknown field"},
           {"gate --config broken.json", "broken.json: (root): invalid JSON"},
           {"gate --config missing.json", "missing.json: cannot read file"},
           {"gate --config typo.json --threads -1", "--threads"}}) {
    INFO(args);
    const CliRun r = run_cli(dir.path, args + " -o out.json");
    check_usage_error(r);
    CHECK(r.err.find(field) != std::string::npos);
    CHECK_FALSE(fs::exists(dir.path / "out.json"));
  }
}

TEST_CASE("gate: report JSON", "[gate]") {
  GateReport r;
  r.checks.push_back({"corpus.a.exact.max_rel_error", 1e-16, 1e-13, true, ""});
  r.checks.push_back({"corpus.a.riemann.max_rel_error", std::numeric_limits<double>::infinity(), 1,
                      false, "ray 0: boom"});
  const auto j = to_json(r);
  CHECK(j["pass"] == false);
  CHECK(j["failures"] == 1);
  CHECK(j["checks"][1]["measured"].is_null());  // JSON has no inf
  CHECK(j["checks"][1]["note"] == "ray 0: boom");
  CHECK_FALSE(j["checks"][0].contains("note"));
}
