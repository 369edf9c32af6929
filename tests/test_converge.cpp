// `rayint converge` (cli/converge_command.cpp, studies/convergence.hpp): the order fit on
// synthetic errors with a known order, riemann converging on a trilinear grid scene at an order
// >= 1 (midpoint steps, kinks at the cube faces), an external command that ignores the step
// flagged (order ~0, exit 1, the JSON still written), a failing command shown as failed, nerf
// (NeRF's quadrature) against riemann, --worst and --error-map-dir, and bad usage refused with
// one line.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"
#include "scene_builders.hpp"
#include "rayint/studies/convergence.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

namespace {

json grid_scene() {
  return {{"medium", {{"type", "grid"}, {"grid", sine_grid(5, 0.3, 0.6, 1.1, 1.7, 0.9)}}},
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
                                 "--steps 0.1,0.05", "--steps 0.1,0.05 --methods nerf:at=far",
                                 "--steps 0.1,0.05 --methods nerf:n=4", "--steps 0.1,0.05 --methods nerfs",
                                 "--steps 0.1,0.05 --methods pl_nerf", "--steps 0.1,0.05 --methods riemann --worst -1",
                                 "--steps 0.1,0.05 --command 'echo {step}'"}) {
    const CliRun r = run_cli(dir.path, "converge scene.json " + args + " -o out.json");
    INFO(args << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(line_count(r.err) == 1);
    CHECK_FALSE(fs::exists(dir.path / "out.json"));
  }
}

namespace {

// A .npy file of float64 values (format 1.0): its header text and its values.
std::pair<std::string, std::vector<double>> read_npy(const fs::path& path) {
  const std::string bytes = slurp(path);
  REQUIRE(bytes.size() > 10);
  REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
  const std::size_t header_len = static_cast<unsigned char>(bytes[8]) + 256u * static_cast<unsigned char>(bytes[9]);
  const std::string header = bytes.substr(10, header_len);
  std::vector<double> values((bytes.size() - 10 - header_len) / sizeof(double));
  std::memcpy(values.data(), bytes.data() + 10 + header_len, values.size() * sizeof(double));
  return {header, values};
}

}  // namespace

TEST_CASE("converge: nerf at the midpoint is riemann's sum, nerf at the near end converges at first order",
          "[converge]") {
  TempDir dir;
  dir.write("scene.json", grid_scene().dump());
  const std::string steps = "--steps 0.2,0.1,0.05,0.025,0.0125 --threads 1";
  REQUIRE(run_cli(dir.path, "converge scene.json " + steps + " --methods riemann -o r.json").status == 0);
  REQUIRE(run_cli(dir.path, "converge scene.json " + steps + " --methods nerf -o n.json").status == 0);
  const CliRun near = run_cli(dir.path, "converge scene.json " + steps +
                                            " --methods nerf:at=near --expect-order 1 --order-tolerance 0.3 -o near.json");
  INFO(near.err);
  CHECK(near.status == 0);
  const json r = json::parse(slurp(dir.path / "r.json"));
  const json n = json::parse(slurp(dir.path / "n.json"));
  const json e = json::parse(slurp(dir.path / "near.json"));
  REQUIRE(n["rows"].size() == 5);
  for (std::size_t i = 0; i < 5; ++i) {
    // Same samples, same sum (T alpha kappa vs riemann's S alpha / sigma): equal to rounding.
    INFO("step " << i);
    CHECK(n["rows"][i]["candidate"].get<std::string>().rfind("nerf:n=", 0) == 0);
    for (const char* stat : {"median", "p95", "max"})
      CHECK(std::abs(n["rows"][i][stat].get<double>() - r["rows"][i][stat].get<double>()) <=
            1e-12 * r["exact_peak"].get<double>());
    CHECK(e["rows"][i]["candidate"].get<std::string>().find(":at=near") != std::string::npos);
  }
  WARN("nerf at=near: " << e["fits"]["median"].dump() << " riemann: " << r["fits"]["median"].dump());
  // The eye-side sample (NeRF 2020's t_i) is a left Riemann sum: first order; the midpoint's is
  // second order on this smooth-but-kinked field (docs/convergence.md: 1.96 over 7 steps).
  REQUIRE(e["fits"]["median"]["order"].is_number());
  const double near_order = e["fits"]["median"]["order"].get<double>();
  CHECK(near_order > 0.7);
  CHECK(near_order < 1.4);
  CHECK(r["fits"]["median"]["order"].get<double>() > near_order + 0.4);
  // And the near-end errors are larger than the midpoint's at every step.
  for (std::size_t i = 0; i < 5; ++i) CHECK(e["rows"][i]["median"].get<double>() > r["rows"][i]["median"].get<double>());
}

TEST_CASE("converge: --worst lists the largest errors with rays that replay them, --error-map-dir writes each step's map",
          "[converge]") {
  TempDir dir;
  dir.write("scene.json", grid_scene().dump());
  const CliRun run = run_cli(dir.path, "converge scene.json --steps 0.4,0.1 --methods nerf:at=near --worst 3 "
                                       "--error-map-dir maps --threads 1 -o c.json");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const json j = json::parse(slurp(dir.path / "c.json"));
  for (std::size_t i = 0; i < 2; ++i) {
    const json& row = j["rows"][i];
    REQUIRE(row["worst"].size() == 3);
    CHECK(row["worst"][0]["error"].get<double>() == row["max"].get<double>());
    CHECK(row["worst"][0]["error"].get<double>() >= row["worst"][1]["error"].get<double>());
    CHECK(row["worst"][1]["error"].get<double>() >= row["worst"][2]["error"].get<double>());
    // The listed error is the largest channel difference of the listed values.
    double d = 0.0;
    for (std::size_t c = 0; c < 3; ++c)
      d = std::max(d, std::abs(row["worst"][0]["candidate"][c].get<double>() - row["worst"][0]["exact"][c].get<double>()));
    CHECK(d == row["worst"][0]["error"].get<double>());
    // The map: H x W = 8 x 10, its largest value the row's max, its file named in the row.
    const fs::path map = dir.path / ("maps/step-" + std::to_string(i) + ".npy");
    REQUIRE(fs::exists(map));
    CHECK(row["error_map"].get<std::string>() == "maps/step-" + std::to_string(i) + ".npy");
    const auto [header, values] = read_npy(map);
    CHECK(header.find("'shape': (8, 10)") != std::string::npos);
    REQUIRE(values.size() == 80);
    CHECK(*std::max_element(values.begin(), values.end()) == row["max"].get<double>());
    const int x = row["worst"][0]["x"].get<int>(), y = row["worst"][0]["y"].get<int>();
    CHECK(values[static_cast<std::size_t>(y * 10 + x)] == row["max"].get<double>());
  }
  // Replay the worst pixel of the coarse step: the scene with that ray as its one explicit ray,
  // rendered exactly, gives the listed exact value.
  const json& w = j["rows"][0]["worst"][0];
  json replay = grid_scene();
  replay.erase("camera");
  replay["rays"] = json::array({{{"origin", w["ray"]["origin"]}, {"direction", w["ray"]["direction"]}}});
  dir.write("replay.json", replay.dump());
  REQUIRE(run_cli(dir.path, "render replay.json -o replay.npy -q").status == 0);
  const auto [rh, rv] = read_npy(dir.path / "replay.npy");
  REQUIRE(rv.size() == 3);
  for (std::size_t c = 0; c < 3; ++c) CHECK(std::abs(rv[c] - w["exact"][c].get<double>()) <= 1e-12);
}
