// `rayint check`: the pass rule, the comparison against the exact values (and an analytic case
// computed here independently, Williams & Max Eq. 6), candidate parsing and matching with their
// one-line messages, the JSON diff, the CLI's exit statuses, and the worked example of
// docs/candidate-format.md run as documented.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include "test_paths.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/report/check_json.hpp"
#include "rayint/input/case_reader.hpp"
#include "cli_harness.hpp"
#include "input_text.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::Tolerances;
namespace fs = std::filesystem;

namespace {

constexpr const char* kCandidateSource = "theirs.json";

// The paper's Fig. 2 interval with a per-channel colour, two rays.
const std::string kCase = rayint::test::fig2_case_text(R"([
    {"segments": [{"length": 1.0, "scalar": [0.0, 1.0]}]},
    {"background": [0.5, 0.5, 0.5], "segments": [{"length": 1.0, "scalar": [1.0, 0.0]}]}
  ])");

const std::string kCandidate = R"({
  "case": "fig2",
  "renderer": "test renderer",
  "rays": [{"intensity": [1, 0.5, 0.1]}, {"index": 1, "intensity": [1.2, 0.7, 0.3]}]
})";

Case fig2() { return parse_case_text(kCase, "fig2.json"); }

std::string with(std::string_view from, std::string_view to, std::string text = kCandidate) {
  return rayint::test::replace_first(std::move(text), from, to);
}

// `<candidate file>: <path>: <what>` on one line.
void check_error(const std::string& text, const std::string& path, const std::string& what) {
  rayint::test::check_one_line_error(
      rayint::test::input_error_of(
          [&] { require_candidate_matches(parse_candidate_text(text, kCandidateSource), fig2()); }),
      kCandidateSource, path, what);
}

// The exact intensities of every ray of `c`, as a candidate.
Candidate exact_candidate(const Case& c) {
  Candidate cand;
  cand.case_name = c.name;
  cand.source = "exact.json";
  const ExactIntegrator exact(c.transfer);
  for (const Ray& ray : c.rays) cand.intensity.push_back(exact.integrate(ray, nullptr).intensity);
  return cand;
}

// A ray whose exact intensity is 0 (zero density, black background), checked without the
// reference against a candidate that gives `got`.
CheckResult check_dark(const Rgb& got, CheckOptions options = {}) {
  static const Case dark = parse_case_text(
      R"({"name": "dark", "transfer_function": {"density": [[0, 0]], "color": [[0, 1]]},
          "rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]}]})",
      "dark.json");
  Candidate d;
  d.case_name = "dark";
  d.intensity = {got};
  options.with_reference = false;
  return check_candidate(dark, d, options);
}

using rayint::test::CliRun;
using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;

}  // namespace

// ---------------------------------------------------------------------------------------------
// The pass rule.

TEST_CASE("pass rule: within the absolute OR the relative tolerance, boundaries included",
          "[check]") {
  // Relative only: allowance rel_tol * |expected|.
  CHECK(within_tolerance(1.0 + 0.5e-6, 1.0, 1e-6, 0.0));
  CHECK_FALSE(within_tolerance(1.0 + 2e-6, 1.0, 1e-6, 0.0));
  // Exactly at the allowance passes (<=): 0.75 - 0.5 = 0.25 = 0.5 * 0.5, all exact in binary.
  CHECK(within_tolerance(0.75, 0.5, 0.5, 0.0));
  CHECK(within_tolerance(0.5 - 0.25, 0.5, 0.0, 0.25));
  // The larger allowance wins: absolute where |expected| is small, relative where it is large.
  CHECK(within_tolerance(1e-10, 0.0, 1e-6, 1e-9));
  CHECK_FALSE(within_tolerance(1e-10, 0.0, 1e-6, 0.0));  // expected 0: rel alone needs got == 0
  CHECK(within_tolerance(0.0, 0.0, 0.0, 0.0));
  CHECK(within_tolerance(1e6 + 0.5, 1e6, 1e-6, 1e-9));
  // Below the expected value as well as above; a negative value is just a wrong answer.
  CHECK(within_tolerance(1.0 - 0.5e-6, 1.0, 1e-6, 0.0));
  CHECK_FALSE(within_tolerance(-0.1, 0.1, 1e-6, 0.0));
  // Anything non-finite fails, whatever the tolerances.
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(within_tolerance(nan, 1.0, 1.0, 1.0));
  CHECK_FALSE(within_tolerance(inf, inf, 1.0, 1.0));
  CHECK_FALSE(within_tolerance(1.0, nan, 1.0, 1.0));
}

// ---------------------------------------------------------------------------------------------
// The comparison.

TEST_CASE("the exact values themselves pass with zero error, and the reference agrees", "[check]") {
  const Case c = read_case_file(RAYINT_SOURCE_DIR + "/cases/paper-figure-2.json");
  CheckOptions opt;
  opt.rel_tol = 0.0;
  opt.abs_tol = 0.0;
  const CheckResult r = check_candidate(c, exact_candidate(c), opt);
  CHECK(r.pass);
  CHECK(r.case_name == "paper-figure-2");
  CHECK(r.candidate_source == "exact.json");
  REQUIRE(r.rays.size() == c.rays.size());
  CHECK(r.summary.rays == c.rays.size());
  CHECK(r.summary.channels == 3 * c.rays.size());
  CHECK(r.summary.failed_channels == 0);
  CHECK(r.summary.max_abs_error == 0.0);
  for (const RayCheck& ray : r.rays) {
    CHECK(ray.pass);
    for (const ChannelCheck& ch : ray.channel) {
      CHECK(ch.abs_error == 0.0);
      CHECK(ch.rel_error == 0.0);
      INFO("expected " << ch.expected << " reference " << ch.reference);
      CHECK(ch.expected_error <= Tolerances::exact_rel * std::fabs(ch.reference));
    }
  }
  CHECK(r.summary.expected_max_rel_uncertainty <= Tolerances::exact_rel);
}

TEST_CASE("an analytic candidate (Eq. 6, constant kappa and rho) passes at the exact tolerance",
          "[check]") {
  // I = kappa (1 - exp(-rho L)) + I0 exp(-rho L) for constant rho and kappa (Williams & Max
  // Eq. 6), computed here from the case's numbers without any rayint integrator.
  const Case c = read_case_file(RAYINT_SOURCE_DIR + "/cases/constant-kappa-and-rho.json");
  Candidate cand;
  cand.case_name = c.name;
  for (const Ray& ray : c.rays) {
    double L = 0.0;
    for (const Segment& s : ray.segments) L += s.length;
    Rgb I{};
    for (int k = 0; k < kChannels; ++k) {
      const double rho = c.transfer.density[k].value.front();
      const double kappa = c.transfer.color[k].value.front();
      I[k] = kappa * -std::expm1(-rho * L) + ray.background[k] * std::exp(-rho * L);
    }
    cand.intensity.push_back(I);
  }
  CheckOptions opt;
  opt.rel_tol = Tolerances::exact_rel;
  const CheckResult r = check_candidate(c, cand, opt);
  INFO("max rel error " << r.summary.max_rel_error);
  CHECK(r.pass);
  // And a 1e-3 relative error in one channel fails exactly that channel and that ray.
  cand.intensity[2][1] *= 1.0 + 1e-3;
  opt.rel_tol = 1e-6;
  const CheckResult f = check_candidate(c, cand, opt);
  CHECK_FALSE(f.pass);
  CHECK(f.summary.failed_channels == 1);
  CHECK(f.summary.failed_rays == 1);
  CHECK_FALSE(f.rays[2].pass);
  CHECK_FALSE(f.rays[2].channel[1].pass);
  CHECK(f.rays[2].channel[0].pass);
  CHECK(f.summary.worst_ray == 2);
  CHECK(f.summary.worst_channel == 1);
  CHECK(f.summary.max_rel_error == Approx(1e-3).epsilon(1e-6));
  CHECK(f.rays[2].channel[1].allowed == 1e-6 * std::fabs(f.rays[2].channel[1].expected));
}

TEST_CASE("errors: abs = |got - expected|, rel = abs / |expected|, inf when expected is 0",
          "[check]") {
  const Case c = fig2();
  Candidate cand = exact_candidate(c);
  const double e0 = cand.intensity[0][0];
  cand.intensity[0][0] = e0 + 0.25;
  CheckOptions opt;
  opt.with_reference = false;
  opt.rel_tol = 0.0;
  opt.abs_tol = 0.5;
  const CheckResult r = check_candidate(c, cand, opt);
  const ChannelCheck& ch = r.rays[0].channel[0];
  CHECK(ch.expected == e0);
  CHECK(ch.got == e0 + 0.25);
  CHECK(ch.abs_error == std::fabs((e0 + 0.25) - e0));
  CHECK(ch.rel_error == ch.abs_error / e0);
  CHECK(ch.allowed == 0.5);
  CHECK(ch.pass);
  CHECK(r.pass);
  // Without the reference its fields stay NaN.
  CHECK(std::isnan(ch.reference));
  CHECK(std::isnan(ch.expected_error));
  CHECK(std::isnan(r.summary.expected_max_rel_uncertainty));

  // A ray whose exact intensity is 0 (zero density, black background).
  const CheckResult z = check_dark(Rgb{0.0, 1e-12, 0.0});
  CHECK(z.rays[0].channel[0].expected == 0.0);
  CHECK(z.rays[0].channel[0].rel_error == 0.0);
  CHECK(z.rays[0].channel[0].pass);
  CHECK(std::isinf(z.rays[0].channel[1].rel_error));
  CHECK_FALSE(z.rays[0].channel[1].pass);
  CheckOptions tight;
  tight.abs_tol = 1e-12;
  CHECK(check_dark(Rgb{0.0, 1e-12, 0.0}, tight).pass);
}

TEST_CASE("check_candidate refuses a candidate of the wrong size and bad tolerances", "[check]") {
  const Case c = fig2();
  Candidate cand = exact_candidate(c);
  cand.intensity.pop_back();
  CHECK_THROWS_AS(check_candidate(c, cand, CheckOptions{}), std::invalid_argument);
  cand = exact_candidate(c);
  CheckOptions opt;
  opt.rel_tol = -1.0;
  CHECK_THROWS_AS(check_candidate(c, cand, opt), std::invalid_argument);
  opt.rel_tol = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(check_candidate(c, cand, opt), std::invalid_argument);
  opt.rel_tol = 1e-6;
  opt.abs_tol = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(check_candidate(c, cand, opt), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Candidate files.

TEST_CASE("a valid candidate round-trips", "[check][candidate]") {
  const Candidate c = parse_candidate_text(kCandidate, kCandidateSource);
  CHECK(c.case_name == "fig2");
  CHECK(c.renderer == "test renderer");
  CHECK(c.source == kCandidateSource);
  REQUIRE(c.intensity.size() == 2);
  CHECK(c.intensity[0] == Rgb{1.0, 0.5, 0.1});
  CHECK(c.intensity[1] == Rgb{1.2, 0.7, 0.3});
  CHECK_NOTHROW(require_candidate_matches(c, fig2()));
  // renderer is optional; negative intensities are wrong answers, not bad input.
  const Candidate n = parse_candidate_text(
      with(R"("renderer": "test renderer",)", "", with("[1, 0.5, 0.1]", "[-1, -0.0, 0]")),
      kCandidateSource);
  CHECK(n.renderer.empty());
  CHECK(n.intensity[0] == Rgb{-1.0, 0.0, 0.0});
}

TEST_CASE("candidate: invalid JSON names the line and column", "[check][candidate]") {
  check_error(with(R"("case": "fig2",)", R"("case": "fig2",,)"), "(root)",
              "invalid JSON at line 2, column 18");
  check_error("", "(root)", "invalid JSON at line 1, column 1");
  check_error(kCandidate + " trailing", "(root)", "invalid JSON");
  check_error(with("[1, 0.5, 0.1]", "[NaN, 0.5, 0.1]"), "(root)", "invalid JSON");
  check_error(with("{", "{ /* comment */"), "(root)", "invalid JSON");
}

TEST_CASE("candidate: wrong types name the field", "[check][candidate]") {
  check_error("[]", "(root)", "must be an object, got array");
  check_error(with(R"("case": "fig2")", R"("case": 2)"), "case", "must be a non-empty string");
  check_error(with(R"("case": "fig2")", R"("case": "")"), "case", "must be a non-empty string");
  check_error(with(R"("renderer": "test renderer")", R"("renderer": 2.3)"), "renderer",
              "must be a string, got number");
  check_error(R"({"case": "fig2", "rays": {}})", "rays", "must be a non-empty array");
  check_error(R"({"case": "fig2", "rays": []})", "rays", "must be a non-empty array");
  check_error(with(R"({"intensity": [1, 0.5, 0.1]})", "[1, 0.5, 0.1]"), "rays[0]",
              "must be an object, got array");
  check_error(with("[1, 0.5, 0.1]", R"("white")"), "rays[0].intensity",
              "must be an array of 3 numbers [r, g, b], got string");
  check_error(with("[1, 0.5, 0.1]", R"([1, "0.5", 0.1])"), "rays[0].intensity[1]",
              "must be a finite number, got string");
  check_error(with(R"("index": 1)", R"("index": "1")"), "rays[1].index", "must be 1");
}

TEST_CASE("candidate: missing, unknown and duplicate fields", "[check][candidate]") {
  check_error(with(R"("case": "fig2",)", ""), "case", "missing required field");
  check_error(R"({"case": "fig2"})", "rays", "missing required field");
  check_error(with(R"({"intensity": [1, 0.5, 0.1]})", R"({"colour": [1, 0.5, 0.1]})"),
              "rays[0].colour", "unknown field (expected index, intensity)");
  check_error(with(R"("renderer")", R"("renderr")"), "renderr",
              "unknown field (expected case, renderer, rays)");
  check_error(with(R"("case": "fig2",)", R"("case": "fig2", "case": "fig2",)"), "case",
              "duplicate field");
}

TEST_CASE("candidate: non-finite numbers are rejected at their field", "[check][candidate]") {
  check_error(with("[1.2, 0.7, 0.3]", "[1.2, 1e999, 0.3]"), "rays[1].intensity[1]",
              "must be finite, got 1e999");
  check_error(with("[1.2, 0.7, 0.3]", "[1.2, 0.7, -1e400]"), "rays[1].intensity[2]",
              "must be finite");
  check_error(with("[1, 0.5, 0.1]", "[null, 0.5, 0.1]"), "rays[0].intensity[0]",
              "must be a finite number, got null (JSON has no NaN or Inf)");
}

TEST_CASE("candidate: a candidate that does not match the case", "[check][candidate]") {
  check_error(with(R"("case": "fig2")", R"("case": "fig3")"), "case",
              R"(is "fig3" but the case file fig2.json is named "fig2")");
  check_error(with(R"(, {"index": 1, "intensity": [1.2, 0.7, 0.3]})", ""), "rays",
              "has 1 entries but the case file fig2.json has 2 rays");
  check_error(with(R"("intensity": [1.2, 0.7, 0.3]})",
                   R"("intensity": [1.2, 0.7, 0.3]}, {"intensity": [1, 1, 1]})"),
              "rays", "has 3 entries but the case file fig2.json has 2 rays");
  check_error(with("[1, 0.5, 0.1]", "[1, 0.5, 0.1, 1]"), "rays[0].intensity",
              "must be an array of 3 numbers [r, g, b], got an array of 4");
  check_error(with("[1, 0.5, 0.1]", "[1]"), "rays[0].intensity",
              "must be an array of 3 numbers [r, g, b], got an array of 1");
  check_error(with(R"("index": 1)", R"("index": 0)"), "rays[1].index",
              "must be 1 (entries follow the case's rays in order), got 0");
}

TEST_CASE("candidate: unreadable files name the file", "[check][candidate]") {
  const std::string missing = RAYINT_SOURCE_DIR + "/cases/no-such-candidate.json";
  try {
    read_candidate_file(missing, fig2());
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == missing + ": cannot read file (No such file or directory)");
  }
  CHECK_THROWS_AS(read_candidate_file(RAYINT_SOURCE_DIR + "/cases", fig2()), InputError);
}

// ---------------------------------------------------------------------------------------------
// The diff.

TEST_CASE("the diff: documented keys in order, per ray and channel, null for infinity",
          "[check][diff]") {
  const Case c = fig2();
  Candidate cand = exact_candidate(c);
  cand.renderer = "r1";
  cand.intensity[1][2] += 1.0;
  const CheckResult r = check_candidate(c, cand, CheckOptions{});
  const nlohmann::ordered_json j = check_report_json(r);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  CHECK(keys == std::vector<std::string>{"tool", "report", "pass", "case", "candidate", "expected",
                                         "rule", "tolerance", "summary", "rays"});
  CHECK(j["pass"] == false);
  CHECK(j["case"]["name"] == "fig2");
  CHECK(j["case"]["file"] == "fig2.json");
  CHECK(j["candidate"]["file"] == "exact.json");
  CHECK(j["candidate"]["renderer"] == "r1");
  CHECK(j["tolerance"]["rel"] == 1e-6);
  CHECK(j["tolerance"]["abs"] == 0.0);
  CHECK(j["summary"]["failed_channels"] == 1);
  CHECK(j["summary"]["worst"]["ray"] == 1);
  CHECK(j["summary"]["worst"]["channel"] == "b");
  REQUIRE(j["rays"].size() == 2);
  CHECK(j["rays"][0]["pass"] == true);
  CHECK(j["rays"][1]["pass"] == false);
  const auto& b = j["rays"][1]["channels"][2];
  CHECK(b["channel"] == "b");
  CHECK(b["pass"] == false);
  CHECK(b["expected"].get<double>() == r.rays[1].channel[2].expected);
  CHECK(b["got"].get<double>() == cand.intensity[1][2]);
  CHECK(b.contains("reference"));
  CHECK(b.contains("expected_error"));

  // Without the reference, no reference fields; an infinite rel_error is written as null.
  const nlohmann::ordered_json z = check_report_json(check_dark(Rgb{0.0, 1.0, 0.0}));
  CHECK(z["rays"][0]["channels"][1]["rel_error"].is_null());
  CHECK(z["rays"][0]["channels"][0]["rel_error"] == 0.0);
  CHECK_FALSE(z["rays"][0]["channels"][0].contains("reference"));
  CHECK_FALSE(z["summary"].contains("expected_max_rel_uncertainty"));
}

// ---------------------------------------------------------------------------------------------
// The CLI (bad input has its own file, test_cli_bad_input.cpp).

TEST_CASE("rayint check: exit 0 on pass, 1 on fail, the diff to stdout or --output",
          "[check][cli]") {
  const TempDir dir;
  const Case c = fig2();
  dir.write("fig2.json", kCase);
  const Candidate exact = exact_candidate(c);
  auto candidate_text = [](const Candidate& cand) {
    nlohmann::json j = {{"case", cand.case_name}, {"rays", nlohmann::json::array()}};
    for (const Rgb& I : cand.intensity) j["rays"].push_back({{"intensity", I}});
    return j.dump();
  };
  dir.write("good.json", candidate_text(exact));
  Candidate off = exact;
  off.intensity[0][0] *= 1.01;
  dir.write("bad.json", candidate_text(off));

  const CliRun pass = run_cli(dir.path, "check fig2.json --candidate good.json --rel-tol 1e-12");
  CHECK(pass.status == 0);
  CHECK(pass.err.rfind("rayint check: PASS: good.json vs fig2.json: 0 of 6 channels", 0) == 0);
  const auto diff = nlohmann::json::parse(pass.out);
  CHECK(diff["pass"] == true);
  CHECK(diff["tolerance"]["rel"] == 1e-12);

  const CliRun fail = run_cli(dir.path, "check fig2.json --candidate bad.json --output diff.json");
  CHECK(fail.status == 1);
  CHECK(fail.out.empty());
  CHECK(fail.err.rfind("rayint check: FAIL: bad.json vs fig2.json: 1 of 6 channels in 1 of 2 rays",
                       0) == 0);
  const auto written = nlohmann::json::parse(slurp(dir.path / "diff.json"));
  CHECK(written["pass"] == false);
  CHECK(written["rays"][0]["channels"][0]["pass"] == false);

  // A 1 % error passes with --rel-tol 0.02, and with an absolute tolerance alone.
  CHECK(run_cli(dir.path, "check fig2.json --candidate bad.json --rel-tol 0.02").status == 0);
  CHECK(run_cli(dir.path,
                "check fig2.json --candidate bad.json --rel-tol 0 --abs-tol 0.1 "
                "--no-reference -o diff2.json")
            .status == 0);
  const auto no_ref = nlohmann::json::parse(slurp(dir.path / "diff2.json"));
  CHECK_FALSE(no_ref["rays"][0]["channels"][0].contains("reference"));
}

// ---------------------------------------------------------------------------------------------
// The worked example of docs/candidate-format.md, run as documented.

namespace {

// The fenced block after `<!-- example: NAME -->`.
std::string doc_block(const std::string& doc, const std::string& name) {
  const std::string marker = "<!-- example: " + name + " -->";
  const auto at = doc.find(marker);
  REQUIRE(at != std::string::npos);
  const auto open = doc.find("```", at);
  const auto body = doc.find('\n', open) + 1;
  const auto close = doc.find("\n```", body);
  REQUIRE((open != std::string::npos && close != std::string::npos));
  return doc.substr(body, close - body + 1);
}

// Same structure, strings and booleans; numbers equal to `rel` (or 1e-15 absolute, for the
// reference's last-digit differences in `expected_error` ~ 1e-17).
void require_same_json(const nlohmann::json& a, const nlohmann::json& b, const std::string& path,
                       double rel) {
  INFO("at " << path << ": documented " << a.dump() << ", got " << b.dump());
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    CHECK(std::fabs(x - y) <= rel * std::max(std::fabs(x), std::fabs(y)) + 1e-15);
    return;
  }
  REQUIRE(a.type() == b.type());
  if (a.is_object()) {
    REQUIRE(a.size() == b.size());
    for (const auto& item : a.items()) {
      REQUIRE(b.contains(item.key()));
      require_same_json(item.value(), b[item.key()], path + "." + item.key(), rel);
    }
  } else if (a.is_array()) {
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      require_same_json(a[i], b[i], path + "[" + std::to_string(i) + "]", rel);
  } else {
    CHECK(a == b);
  }
}

}  // namespace

TEST_CASE("docs/candidate-format.md: the worked example gives the documented output",
          "[check][cli][docs]") {
  const std::string doc = slurp(RAYINT_SOURCE_DIR + "/docs/candidate-format.md");
  const TempDir dir;
  dir.write("two-rays.json", doc_block(doc, "two-rays.json"));
  dir.write("my-renderer.json", doc_block(doc, "my-renderer.json"));

  // "$ rayint ARGS", the stderr line, "$ echo $?", the exit status.
  std::istringstream session(doc_block(doc, "command"));
  std::string command, stderr_line, echo, status;
  std::getline(session, command);
  std::getline(session, stderr_line);
  std::getline(session, echo);
  std::getline(session, status);
  REQUIRE(command.rfind("$ rayint ", 0) == 0);
  REQUIRE(echo == "$ echo $?");

  const CliRun run = run_cli(dir.path, command.substr(std::string("$ rayint ").size()));
  CHECK(run.status == std::stoi(status));
  CHECK(run.out.empty());
  CHECK(run.err == stderr_line + "\n");
  // 1e-12: the documented numbers are the Release build's; the reference's last digits (and
  // hence `expected_error`, ~1e-17) may move when the reference improves.
  require_same_json(nlohmann::json::parse(doc_block(doc, "diff.json")),
                    nlohmann::json::parse(slurp(dir.path / "diff.json")), "diff", 1e-12);
}
