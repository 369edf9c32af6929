// Tabulated phase functions for P_N (pn.hpp, legendre_from_table; slab scenes' "legendre" and
// "tabulated" phase types): coefficients of a table whose moments are known in closed form, a
// Henyey-Greenstein table against the analytic HG, and the CLI (only pn takes them; bad tables
// are one line naming the field, exit 2). Bounds: tests/tolerances_ground_table_diffusion.hpp.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "rayint/core/math.hpp"
#include "rayint/scattering/pn.hpp"
#include "scatter_fixtures.hpp"
#include "tolerances_ground_table_diffusion.hpp"

using namespace rayint;
using rayint::test::PnGroundTolerances;

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

double hg(double g, double x) { return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * x, 1.5)); }

// HG g tabulated at n + 1 cosines, uniform in the scattering angle (denser where HG peaks).
void hg_table(double g, int n, std::vector<double>& x, std::vector<double>& y) {
  x.clear();
  y.clear();
  for (int i = 0; i <= n; ++i) {
    const double c = i == 0 ? -1.0 : i == n ? 1.0 : -std::cos(kPi * i / n);
    x.push_back(c);
    y.push_back(hg(g, c));
  }
}

std::string scene_with_phase(const std::string& phase) {
  return R"({"name": "t", "medium": {"type": "slab", "optical_thickness": 2, "albedo": 0.95},
    "phase": )" + phase + R"(, "lights": [{"type": "beam", "mu0": 0.6}],
    "detectors": {"mu_up": [0.2, 1], "mu_down": [0.2, 1]}})";
}

}  // namespace

TEST_CASE("Legendre coefficients of a linear phase table are exact", "[pn][table]") {
  // p = (1 + a x) / (4 pi) is linear, so a two-point table is exact: chi_1 = a/3, chi_l = 0 for
  // l >= 2. Unnormalised (times 7) and split at interior points, the same.
  const double a = 0.6;
  for (const std::vector<double>& x : {std::vector<double>{-1, 1}, std::vector<double>{-1, -0.3, 0.25, 1}}) {
    std::vector<double> y;
    for (double c : x) y.push_back(7 * (1 + a * c) / (4 * kPi));
    const std::vector<double> chi = legendre_from_table(x, y, 40);
    REQUIRE(chi.size() == 41);
    CHECK(chi[0] == 1);
    double worst = std::fabs(chi[1] - a / 3);
    for (std::size_t l = 2; l < chi.size(); ++l) worst = std::max(worst, std::fabs(chi[l]));
    INFO("largest deviation from the closed form " << std::scientific << std::setprecision(3) << worst);
    CHECK(worst <= PnGroundTolerances::table_exact_abs);
  }
  // A V-shaped table p ~ |x|: chi_2 = 1/4 by hand (int |x| P_2 = 1/4, int |x| = 1), odd moments 0.
  const std::vector<double> chi = legendre_from_table({-1, 0, 1}, {1, 0, 1}, 3);
  const double worst = std::max({std::fabs(chi[1]), std::fabs(chi[2] - 0.25), std::fabs(chi[3])});
  INFO("V table: largest deviation " << std::scientific << std::setprecision(3) << worst);
  CHECK(worst <= PnGroundTolerances::table_exact_abs);
  // Bad tables.
  CHECK_THROWS_AS(legendre_from_table({-1, 0.5}, {1, 1}, 3), std::invalid_argument);
  CHECK_THROWS_AS(legendre_from_table({-1, 0.5, 0.2, 1}, {1, 1, 1, 1}, 3), std::invalid_argument);
  CHECK_THROWS_AS(legendre_from_table({-1, 1}, {0, 0}, 3), std::invalid_argument);
  CHECK_THROWS_AS(legendre_from_table({-1, 1}, {1, -1}, 3), std::invalid_argument);
}

TEST_CASE("P_N on a tabulated Henyey-Greenstein phase function gives the analytic HG answer", "[pn][table]") {
  SlabProblem p = test::hg_slab(0.75);
  PnOptions o;
  o.order = 31;
  const PnSolution exact = solve_slab_pn(p, o);
  double previous = 1e300;
  for (int n : {256, 1024, 4096}) {
    std::vector<double> x, y;
    hg_table(0.75, n, x, y);
    o.legendre = legendre_from_table(x, y, 255);
    p.phase = PhaseFunction::isotropic();  // the table alone carries the phase function
    const PnSolution tab = solve_slab_pn(p, o);
    p.phase = PhaseFunction::henyey_greenstein(0.75);
    double e = rel(tab.values.flux_up_top, exact.values.flux_up_top);
    e = std::max(e, rel(tab.values.diffuse_down_bottom, exact.values.diffuse_down_bottom));
    for (std::size_t i = 0; i < 2; ++i) {
      e = std::max(e, rel(tab.values.intensity_up_top[i], exact.values.intensity_up_top[i]));
      e = std::max(e, rel(tab.values.intensity_down_bottom[i], exact.values.intensity_down_bottom[i]));
    }
    INFO("table of " << n + 1 << " points: largest relative difference " << e << ", chi_1 " << o.legendre[1]);
    CHECK(e <= PnGroundTolerances::hg_table_rel[n == 256 ? 0 : n == 1024 ? 1 : 2]);
    CHECK(e < previous);  // the linear interpolation's error, falling with the table
    previous = e;
  }
}

TEST_CASE("rayint slab --scene: legendre and tabulated phase functions for pn", "[pn][table][cli]") {
  rayint::test::TempDir dir;
  // Legendre coefficients g^l (l <= 160) are HG: the same numbers as the hg scene.
  std::ostringstream coef;
  coef << std::setprecision(17) << "[1";
  for (int l = 1; l <= 160; ++l) coef << ", " << std::pow(0.75, l);
  coef << "]";
  write_text(dir.path / "hg.json", scene_with_phase(R"({"type": "henyey_greenstein", "g": 0.75})"));
  write_text(dir.path / "leg.json", scene_with_phase(R"({"type": "legendre", "coefficients": )" + coef.str() + "}"));
  std::vector<double> x, y;
  hg_table(0.75, 4096, x, y);
  nlohmann::json pts = nlohmann::json::array();
  for (std::size_t i = 0; i < x.size(); ++i) pts.push_back({x[i], y[i]});
  write_text(dir.path / "tab.json", scene_with_phase(R"({"type": "tabulated", "points": )" + pts.dump() + "}"));
  const auto a = rayint::test::run_cli(dir.path, "slab --scene hg.json --method pn:order=31");
  const auto b = rayint::test::run_cli(dir.path, "slab --scene leg.json --method pn:order=31");
  const auto c = rayint::test::run_cli(dir.path, "slab --scene tab.json --method pn:order=31");
  INFO(a.err << b.err << c.err);
  REQUIRE(a.status == 0);
  REQUIRE(b.status == 0);
  REQUIRE(c.status == 0);
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out), jc = nlohmann::json::parse(c.out);
  CHECK(jb["phase"] == "legendre");
  CHECK(jc["phase"] == "tabulated");
  CHECK(std::fabs(jc["phase_mean_cosine"].get<double>() - 0.75) <= 1e-5);
  for (const char* key : {"flux_up_top", "diffuse_down_bottom"}) {
    CHECK(rel(jb["pn"][key].get<double>(), ja["pn"][key].get<double>()) <= 1e-12);
    CHECK(rel(jc["pn"][key].get<double>(), ja["pn"][key].get<double>()) <= PnGroundTolerances::hg_table_rel[2]);
  }
  // Only pn takes them.
  const auto d = rayint::test::run_cli(dir.path, "slab --scene leg.json --method doubling");
  CHECK(d.status == 2);
  CHECK(d.err.find("--method pn only") != std::string::npos);
  // Bad tables and coefficients: one line naming the field, exit 2, nothing on stdout.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"type": "legendre", "coefficients": [0.9, 0.5]})", "phase.coefficients[0]"},
      {R"({"type": "legendre", "coefficients": [1, 1.0]})", "phase.coefficients[1]"},
      {R"({"type": "legendre", "coefficients": []})", "phase.coefficients"},
      {R"({"type": "tabulated", "points": [[-1, 1], [0.5, 1]]})", "phase.points"},
      {R"({"type": "tabulated", "points": [[-1, 0], [1, 0]]})", "phase.points"},
      {R"({"type": "tabulated", "points": [[-1, 1], [1, -1]]})", "phase.points"},
      {R"({"type": "tabulated"})", "phase"}};
  for (const auto& [phase, field] : bad) {
    write_text(dir.path / "bad.json", scene_with_phase(phase));
    const auto r = rayint::test::run_cli(dir.path, "slab --scene bad.json --method pn");
    INFO(phase << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(field) != std::string::npos);
    CHECK(rayint::test::line_count(r.err) == 1);
    CHECK(r.out.empty());
  }
}
