// Method specs are checked against the one method table (integrators/registry.cpp) before
// anything runs, and a method that fails at run time is a failure in every output (issue 26):
//   - the validator's messages and the bounds of every parameter in the table;
//   - the factories build every method from the table's defaults and every choice;
//   - every entry point refuses an invalid spec with exit 2, one stderr line, nothing written
//     (eval, stress, render, gate's configuration, bench);
//   - `particle` on a case with several transfer functions: null errors, the failure text, a
//     failed count in the JSON summary and the table, exit 1; a gate on it fails;
//   - `rayint methods`, `rayint --version`, `rayint` alone.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "cli_refusal.hpp"
#include "input_text.hpp"
#include "rayint/integrators/integrator.hpp"
#include "transfer_builders.hpp"

namespace {

using rayint::MethodParam;
using rayint::MethodSpecError;
using rayint::parse_method_spec;
using rayint::test::CliRun;
using rayint::test::line_count;
using rayint::test::run_cli;
using rayint::test::TempDir;

// The message parse_method_spec gives for `spec`, or "" if it accepts it.
std::string refusal(const std::string& spec) {
  return rayint::test::error_message_of<MethodSpecError>([&] { parse_method_spec(spec); }, "");
}

std::string number_text(double x) {
  if (x == std::floor(x) && std::fabs(x) < 1e15) return std::to_string(static_cast<long long>(x));
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// Parameters some bounds need to be tried with (the combination rules of their method).
std::string context_for(const std::string& method, const std::string& param) {
  if (method == "preintegrated" && (param == "max_length" || param == "lengths"))
    return ":dims=3:size=2";  // dims=3 parameters; size 2 keeps 4096 planes under 1 GiB
  return "";
}

// The specs named in issue 26, with the line the CLI must print after "rayint: error: --methods ".
struct Invalid {
  const char* spec;
  const char* why;
};
const std::vector<Invalid> kInvalid = {
    {"riemann:n=0", "riemann:n=0: n must be an integer >= 1"},
    {"nerf:n=0", "nerf:n=0: n must be an integer >= 1"},
    {"psi_table:size=1073741824",
     "psi_table:size=1073741824: size must be an integer <= 8192 (the table takes 16 B per "
     "entry: 1 GiB at 8192)"},
    {"ode:rtol=0", "ode:rtol=0: rtol must be a number >= 1e-15"},
    {"riemann:n=64.5", "riemann:n=64.5: n must be an integer in [1, 1e9]"},
    {"riemann:n=many", "riemann:n=many: n must be an integer in [1, 1e9]"},
    {"riemann:order=sideways", "riemann:order=sideways: order must be btf or ftb"},
    {"riemann:m=4", "riemann:m=4: unknown parameter 'm' (riemann takes n, dt, order, correction, ref_dt)"},
    {"paper:n=4", "paper:n=4: unknown parameter 'n' (paper takes no parameters)"},
};

const std::string kCase = rayint::test::fig2_case_text(R"([
    {"segments": [{"length": 1.0, "scalar": [0.1, 0.9]}]}
  ])");

}  // namespace

TEST_CASE("method specs: each invalid spec is refused with one line naming it and the range",
          "[methods][specs]") {
  for (const Invalid& x : kInvalid) {
    INFO(x.spec);
    CHECK(refusal(x.spec) == x.why);
  }
  CHECK(refusal("nosuch:n=1").rfind("nosuch:n=1: unknown method 'nosuch' (known: exact, paper, ", 0) == 0);
  CHECK(refusal("riemann:n=4:n=5") == "riemann:n=4:n=5: n given twice");
  CHECK(refusal("riemann:n") == "riemann:n: expected key=value, got 'n'");
  CHECK(refusal("riemann:n=4:") == "riemann:n=4:: expected key=value after ':'");
  // Combinations the method's own check refuses, in the same form.
  CHECK(refusal("riemann:n=4:dt=0.1") == "riemann:n=4:dt=0.1: give n (samples per segment) or dt (step), not both");
  CHECK(refusal("preintegrated:dims=3:size=4096") ==
        "preintegrated:dims=3:size=4096: a table of 12672 MiB exceeds the 1 GiB limit; lower size or lengths");
  CHECK_THROWS_AS(rayint::parse_method_list(""), MethodSpecError);
}

TEST_CASE("method specs: numbers in the forms people type", "[methods][specs]") {
  CHECK(parse_method_spec("riemann:n=1e3").integer("n") == 1000);
  CHECK(parse_method_spec("riemann:n=64").integer("n") == 64);
  CHECK(parse_method_spec("ode:rtol=1e-10").number("rtol") == 1e-10);
  CHECK(parse_method_spec("riemann:dt=.5").number("dt") == 0.5);
  for (const char* bad : {"riemann:n=64.5", "riemann:n=0x40", "riemann:n=inf", "riemann:n=nan",
                          "riemann:n= 64", "riemann:n=64x", "ode:rtol=1e-8e", "riemann:n=1e10"}) {
    INFO(bad);
    CHECK_FALSE(refusal(bad).empty());
  }
}

TEST_CASE("method specs: a report key is the spec as typed, matching uses the canonical form",
          "[methods][specs]") {
  const rayint::MethodSpec a = parse_method_spec("nerf:n=64:at=near");
  const rayint::MethodSpec b = parse_method_spec("nerf:at=near:n=64");
  CHECK(a.label() == "nerf:n=64:at=near");
  CHECK(b.label() == "nerf:at=near:n=64");
  CHECK(a.canonical() == "nerf:at=near:n=64");
  CHECK(a.canonical() == b.canonical());
  CHECK(parse_method_spec("riemann:n=64").label() == "riemann:n=64");  // the gate's baseline key
  CHECK(parse_method_spec("riemann:n=64").canonical() == "riemann:n=64");
}

TEST_CASE("method table: every bound is where the validator puts it", "[methods][specs]") {
  int bounds = 0;
  for (const rayint::MethodSchema& m : rayint::method_table()) {
    for (const MethodParam& p : m.params) {
      if (p.type == MethodParam::Type::choice) continue;
      const std::string at = m.name + context_for(m.name, p.name) + ":" + p.name + "=";
      const double step = p.type == MethodParam::Type::integer ? 1.0 : 0.0;
      if (p.has_min) {
        INFO(at << " min " << p.min);
        const double inside = p.min_exclusive ? (step > 0 ? p.min + 1 : std::nextafter(p.min, 1e300)) : p.min;
        CHECK(refusal(at + number_text(inside)).empty());
        const double outside = p.min_exclusive ? p.min : (step > 0 ? p.min - 1 : std::nextafter(p.min, -1e300));
        CHECK_FALSE(refusal(at + number_text(outside)).empty());
        ++bounds;
      }
      if (p.has_max) {
        INFO(at << " max " << p.max);
        const double inside = p.max_exclusive ? std::nextafter(p.max, -1e300) : p.max;
        CHECK(refusal(at + number_text(inside)).empty());
        const double outside = p.max_exclusive ? p.max : (step > 0 ? p.max + 1 : std::nextafter(p.max, 1e300));
        CHECK_FALSE(refusal(at + number_text(outside)).empty());
        ++bounds;
      }
    }
  }
  CHECK(bounds >= 20);  // the table's integer and number parameters, each tried at its bounds
}

TEST_CASE("method table: every method builds from its defaults and with every choice",
          "[methods][specs]") {
  using rayint::test::line;
  // One density for all channels and a constant colour: every method applies (particle too).
  const rayint::TransferFunctions tf =
      rayint::test::uniform_tf(line(0, 0.5, 1, 2), rayint::test::constant(0.7));
  rayint::Ray ray;
  ray.segments.push_back({1.0, 0.2, 0.8});
  const auto runs = [&](const std::string& text) {
    INFO(text);
    const auto integrator = rayint::make_integrator(parse_method_spec(text), tf);
    const rayint::RayResult r = integrator->integrate(ray, nullptr);
    for (int c = 0; c < rayint::kChannels; ++c) {
      CHECK(std::isfinite(r.intensity[c]));
      CHECK(r.transmittance[c] >= 0.0);  // nerf:last=inf makes it 0
      CHECK(r.transmittance[c] < 1.0);
    }
  };
  for (const rayint::MethodSchema& m : rayint::method_table()) {
    runs(m.name);
    for (const MethodParam& p : m.params)
      for (const std::string& choice : p.choices) {
        std::string spec = m.name + ":" + p.name + "=" + choice;
        if (m.name == "riemann" && p.name == "correction" && choice == "none") spec += ":ref_dt=0.1";
        runs(spec);
      }
  }
}

TEST_CASE("CLI: an invalid method spec is bad input in every command", "[cli][methods][specs]") {
  const TempDir dir;
  dir.write("case.json", kCase);
  const auto refused = [&](const std::string& args, const std::string& line) {
    const CliRun r = rayint::test::check_refused(dir, args);  // nothing written, -o included
    INFO("rayint " << args << "\nstdout: " << r.out << "\nstderr: " << r.err);
    CHECK(r.out.empty());
    CHECK(r.err == "rayint: error: " + line + "\n");
  };
  std::vector<Invalid> specs = kInvalid;
  specs.push_back({"nosuch", ""});
  for (const Invalid& x : specs) {
    const std::string why = *x.why ? x.why : refusal(x.spec);
    refused("eval case.json --no-timing -o out.json --methods " + std::string(x.spec), "--methods " + why);
    refused("eval case.json --no-timing --format table -o out.txt --methods exact," + std::string(x.spec),
            "--methods " + why);
    refused("stress --count 10 --no-worst -o out.txt --methods " + std::string(x.spec), "--methods " + why);
    refused("render case.json -o out.png --compare " + std::string(x.spec), "--compare " + why);
    // gate: the configuration names the method; the line names the file and the key.
    dir.write("gate.json", R"({"corpus": {"cases": ["case.json"], "methods": {")" +
                               std::string(x.spec) + R"(": {"max_rel_error": 1}}}})");
    const std::string tail = why.substr(std::string(x.spec).size() + 2);
    const CliRun g = run_cli(dir.path, "gate --config gate.json -o out.txt");
    INFO("gate: " << g.err);
    CHECK(g.status == 2);
    CHECK(line_count(g.err) == 1);
    CHECK(g.err.find("gate.json") != std::string::npos);
    CHECK(g.err.find(std::string(x.spec) + ": " + tail + "\n") != std::string::npos);
    CHECK_FALSE(rayint::test::fs::exists(dir.path / "out.txt"));
    std::remove((dir.path / "gate.json").c_str());
  }
  // bench sweeps each method along its knob, so it takes names only.
  refused("bench case.json -o out.json --methods riemann:n=0",
          "bench: --methods takes method names (the sweep chooses the settings), got 'riemann:n=0'");
}

TEST_CASE("CLI: particle on a case with several transfer functions fails, and says so everywhere",
          "[cli][methods][failure]") {
  const TempDir dir;
  dir.copy_case("per-channel-densities");
  const CliRun r = run_cli(dir.path, "eval per-channel-densities.json --no-timing -q --methods exact,particle");
  INFO(r.err);
  CHECK(r.status == 1);  // output written, a method failed on some ray
  const auto j = nlohmann::json::parse(r.out);
  const auto& c = j["cases"][0];
  REQUIRE(c["rays"].size() == 3);
  CHECK(j["failed"] == 3);
  for (const auto& ray : c["rays"]) {
    const auto& p = ray["methods"]["particle"];
    CHECK(p["failed"] == true);
    CHECK(p["failure"].get<std::string>().rfind("particle: needs a single transfer function", 0) == 0);
    for (const char* f : {"intensity", "transmittance", "abs_error", "rel_error", "ulp_error",
                          "transmittance_rel_error", "seconds_per_ray"})
      CHECK(p[f].is_null());
    const auto& e = ray["methods"]["exact"];  // the other method is unaffected
    CHECK(e["failed"] == false);
    CHECK(e["rel_error"][0].is_number());
    CHECK_FALSE(e.contains("failure"));
  }
  REQUIRE(c["summary"].size() == 2);
  CHECK(c["summary"][0]["method"] == "exact");
  CHECK(c["summary"][0]["failed"] == 0);
  CHECK(c["summary"][0]["max_rel_error"].is_number());
  CHECK(c["summary"][1]["method"] == "particle");
  CHECK(c["summary"][1]["rays"] == 3);
  CHECK(c["summary"][1]["failed"] == 3);
  CHECK(c["summary"][1]["max_rel_error"].is_null());
  CHECK(c["summary"][1]["first_failure"].get<std::string>().rfind("ray 0: particle: ", 0) == 0);

  const CliRun t = run_cli(dir.path, "eval per-channel-densities.json --no-timing -q --format table --methods exact,particle");
  INFO(t.out);
  CHECK(t.status == 1);
  CHECK(t.out.find("failed") != std::string::npos);  // the column
  CHECK(t.out.find("FAILED per-channel-densities particle on 3 of 3 rays; first: ray 0: particle: ") !=
        std::string::npos);

  // A gate whose method fails fails, whatever its limits allow.
  dir.write("gate.json", R"({"corpus": {"cases": ["per-channel-densities.json"],
      "methods": {"particle": {"max_non_finite": 10}, "exact": {"max_rel_error": 1e-13}}}})");
  const CliRun g = run_cli(dir.path, "gate --config gate.json");
  INFO(g.out << g.err);
  CHECK(g.status == 1);
  CHECK(g.out.find("FAIL corpus.per-channel-densities.particle.failed") != std::string::npos);
  CHECK(g.out.find("PASS corpus.per-channel-densities.exact.max_rel_error") != std::string::npos);
}

TEST_CASE("CLI: rayint methods lists the table the validator uses", "[cli][methods]") {
  const TempDir dir;
  const CliRun r = run_cli(dir.path, "methods --format json");
  REQUIRE(r.status == 0);
  const auto j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& m : j["methods"]) names.push_back(m["name"]);
  // The CLI lists the library's table, then what optional libraries registered (VTK's methods).
  const std::vector<std::string> library = rayint::method_names();
  REQUIRE(names.size() >= library.size());
  CHECK(std::vector<std::string>(names.begin(), names.begin() + static_cast<long>(library.size())) == library);
  bool found = false;
  for (const auto& m : j["methods"])
    if (m["name"] == "riemann")
      for (const auto& p : m["params"])
        if (p["name"] == "n") {
          found = true;
          CHECK(p["type"] == "integer");
          CHECK(p["default"] == "64");
          CHECK(p["min"] == 1);
          CHECK(p["allowed"] == "an integer in [1, 1e9]");
        }
  CHECK(found);
  const CliRun text = run_cli(dir.path, "methods");
  CHECK(text.status == 0);
  CHECK(text.out.find("    n (integer, default 64): an integer in [1, 1e9]. samples per segment") !=
        std::string::npos);
  const CliRun v = run_cli(dir.path, "--version");
  CHECK(v.status == 0);
  CHECK(v.out.rfind("rayint ", 0) == 0);
  const CliRun none = run_cli(dir.path, "");
  CHECK(none.status == 2);
  CHECK(none.err.find("Usage:") != std::string::npos);
  CHECK(none.err.find("eval") != std::string::npos);
}
