// `rayint converge` (cli/converge_command.cpp, studies/convergence.hpp): the order fit on
// synthetic errors with a known order, riemann converging on a trilinear grid scene at an order
// >= 1 (midpoint steps, kinks at the cube faces), an external command that ignores the step
// flagged (order ~0, exit 1, the JSON still written), a failing command shown as failed, and
// bad usage refused with one line.
#include <catch2/catch.hpp>
#include <cmath>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "rayint/studies/convergence.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

namespace {

json grid_scene() {
  json values = json::array();
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) values.push_back(0.3 + 0.6 * std::fabs(std::sin(1.1 * i + 1.7 * j - 0.9 * k)));
  return {{"medium", {{"type", "grid"},
                      {"grid", {{"dims", {5, 5, 5}}, {"origin", {-1, -1, -1}}, {"spacing", {0.5, 0.5, 0.5}}, {"values", values}}}}},
          {"transfer", {{"extinction", {{0, 0}, {0.5, 1.5}, {1, 2.5}}}, {"emission", {{0, 0.2}, {1, 0.9}}}}},
          {"background", {{"color", {0.3, 0.6, 0.9}}}},
          {"camera", {{"position", {0.3, 0.4, 5}}, {"look_at", {0, 0, 0}}, {"fov_deg", 30}, {"width", 10}, {"height", 8}}},
          {"effects", {"absorption", "emission"}}};
}

}  // namespace

TEST_CASE("converge: the order fit recovers a known order and drops the pre-asymptotic steps", "[converge]") {
  // e = 3 h^2 for h <= 0.1, a plateau above: the fit must use the h^2 part only.
  const std::vector<double> h{0.8, 0.4, 0.2, 0.1, 0.05, 0.025};
  std::vector<double> e;
  for (double x : h) e.push_back(x > 0.1 ? 0.03 : 3.0 * x * x);
  const OrderFit f = observed_order(h, e, 1e-12);
  REQUIRE(f.ok);
  CHECK(std::abs(f.order - 2.0) < 1e-12);
  CHECK(f.last == 5);
  CHECK(f.first == 3);  // 0.1, 0.05, 0.025: the plateau's local orders (0 and 1.58) are dropped
  // A constant error (a renderer ignoring the step): order 0.
  const OrderFit flat = observed_order(h, std::vector<double>(h.size(), 0.01), 1e-12);
  REQUIRE(flat.ok);
  CHECK(std::abs(flat.order) < 1e-12);
  // Errors below the floor are not fitted.
  CHECK_FALSE(observed_order(h, std::vector<double>(h.size(), 1e-14), 1e-12).ok);
  const PixelErrorStats s = pixel_error_stats({5, 1, 4, 2, 3});
  CHECK(s.median == 3);
  CHECK(s.max == 5);
  CHECK(s.p95 == 5);
}

TEST_CASE("converge: riemann converges at order >= 1 on a trilinear grid, a step-blind command is flagged",
          "[converge]") {
  TempDir dir;
  dir.write("scene.json", grid_scene().dump());
  const CliRun ok = run_cli(dir.path,
                            "converge scene.json --steps 0.2,0.1,0.05,0.025,0.0125 --methods riemann "
                            "--expect-order 1 --order-tolerance 0.2 --threads 1 -o conv.json");
  INFO(ok.err);
  CHECK(ok.status == 0);
  const json j = json::parse(slurp(dir.path / "conv.json"));
  WARN("riemann on the 5^3 trilinear grid: " << j["fits"].dump());
  REQUIRE(j["fits"]["median"]["order"].is_number());
  CHECK(j["fits"]["median"]["order"].get<double>() >= 0.8);
  CHECK(j["passed"] == true);
  CHECK(j["invariant_to_step"] == false);
  CHECK(j["rows"].size() == 5);

  // A renderer that ignores the step: the image at the coarsest step, copied for every step.
  const std::string coarse = (dir.path / "coarse.pfm").string();
  REQUIRE(run_cli(dir.path, "render scene.json -o coarse.pfm --method absorption=riemann:n=4 "
                            "--method emission=riemann:n=4 --quiet").status == 0);
  const CliRun bad = run_cli(dir.path, "converge scene.json --steps 0.2,0.1,0.05,0.025 --command 'cp " + coarse +
                                           " {out}' --expect-order 1 --threads 1 -o blind.json");
  CHECK(bad.status == 1);
  const json b = json::parse(slurp(dir.path / "blind.json"));
  CHECK(b["passed"] == false);
  CHECK(b["invariant_to_step"] == true);
  REQUIRE(b["fits"]["median"]["order"].is_number());
  CHECK(std::abs(b["fits"]["median"]["order"].get<double>()) < 0.05);

  // A command that fails: its rows are failed with null errors, exit 1.
  const CliRun fails = run_cli(dir.path, "converge scene.json --steps 0.2,0.1 --command 'false {out}' -o f.json");
  CHECK(fails.status == 1);
  const json fj = json::parse(slurp(dir.path / "f.json"));
  CHECK(fj["rows"][0]["failed"] == true);
  CHECK(fj["rows"][0]["median"].is_null());
  CHECK(fj["fits"]["median"]["order"].is_null());
}

TEST_CASE("converge: bad usage is one line, exit 2, nothing written", "[converge]") {
  TempDir dir;
  dir.write("scene.json", grid_scene().dump());
  for (const std::string args : {"--steps 0.1 --methods riemann", "--steps 0.1,-1 --methods riemann",
                                 "--steps 0.1,0.05", "--steps 0.1,0.05 --methods nerf",
                                 "--steps 0.1,0.05 --command 'echo {step}'"}) {
    const CliRun r = run_cli(dir.path, "converge scene.json " + args + " -o out.json");
    INFO(args << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_FALSE(fs::exists(dir.path / "out.json"));
  }
}
