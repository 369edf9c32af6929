// The Lambertian lower boundary (SlabProblem::ground_albedo) in P_N (src/rayint/scattering/pn.hpp)
// against the adding-doubling solver with the ground added exactly (add_lambertian_ground,
// slab.hpp), and that reference against the analog Monte Carlo, which reflects photons at the
// ground itself (no shared formula). No published table with a reflecting ground is in
// cases/scattering/disort_slab.json (DISORT problems 1 and 3 have a black ground).
// Bounds: tests/tolerances_ground_table_diffusion.hpp.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "rayint/core/math.hpp"
#include "rayint/scattering/pn.hpp"
#include "rayint/scattering/slab_doubling.hpp"
#include "rayint/scattering/slab_monte_carlo.hpp"
#include "tolerances_ground_table_diffusion.hpp"

using namespace rayint;
using rayint::test::PnGroundTolerances;

namespace {

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// Largest relative difference over the fluxes and intensities (the direct beam is analytic).
double largest_rel(const SlabValues& a, const SlabValues& ref) {
  double e = std::max(rel(a.flux_up_top, ref.flux_up_top), rel(a.diffuse_down_bottom, ref.diffuse_down_bottom));
  for (std::size_t i = 0; i < ref.intensity_up_top.size(); ++i)
    e = std::max(e, rel(a.intensity_up_top[i], ref.intensity_up_top[i]));
  for (std::size_t i = 0; i < ref.intensity_down_bottom.size(); ++i)
    e = std::max(e, rel(a.intensity_down_bottom[i], ref.intensity_down_bottom[i]));
  return e;
}

SlabProblem ground_problem(double tau, double omega, double A, SlabSource source) {
  SlabProblem p;
  p.tau = tau;
  p.albedo = omega;
  p.ground_albedo = A;
  p.source = source;
  p.mu0 = 0.5;
  p.mu_up = {0.1, 0.5, 1.0};
  p.mu_down = {0.1, 0.5, 1.0};
  return p;
}

}  // namespace

TEST_CASE("P_N with a Lambertian ground converges to the doubling with the ground added", "[pn][ground]") {
  // Thin (1/32), middle (1) and thick (32) slabs, absorbing and conservative, beam and isotropic
  // incidence, HG 0.75 on the middle slab; ground albedo 0.1, 0.5, 1.
  for (double A : {0.1, 0.5, 1.0})
    for (double tau : {0.03125, 1.0, 32.0})
      for (double omega : {0.5, 1.0})
        for (SlabSource src : {SlabSource::beam, SlabSource::isotropic})
          for (bool hg : {false, true}) {
            if (hg && tau != 1.0) continue;
            SlabProblem p = ground_problem(tau, omega, A, src);
            if (hg) p.phase = PhaseFunction::henyey_greenstein(0.75);
            const SlabValues ref = solve_slab_doubling(p);
            const bool thin = tau < 1;
            PnOptions o;
            o.order = 31;
            const double e31 = largest_rel(solve_slab_pn(p, o).values, ref);
            o.order = 127;
            const double e127 = largest_rel(solve_slab_pn(p, o).values, ref);
            INFO("A " << A << " tau " << tau << " omega " << omega << " beam " << (src == SlabSource::beam)
                      << " hg " << hg << ": P31 " << e31 << " P127 " << e127);
            CHECK(e31 <= (thin ? PnGroundTolerances::p31_thin : PnGroundTolerances::p31));
            CHECK(e127 <= (thin ? PnGroundTolerances::p127_thin : PnGroundTolerances::p127));
            // A = 1, omega = 1 under isotropic light: I = 1 everywhere, which every P_N holds
            // exactly; what is left is the doubling's own error (measured <= 3.3e-9).
            if (e31 > 1e-7) CHECK(e127 < e31);
            else CHECK((A == 1.0 && omega == 1.0 && src == SlabSource::isotropic));
          }
}

TEST_CASE("P_N with Mark's boundary conditions and a Lambertian ground converges too", "[pn][ground]") {
  // tau 1, omega 0.9, A 0.6, beam (mu0 0.5) and isotropic light, P127 with Mark's conditions.
  for (SlabSource src : {SlabSource::beam, SlabSource::isotropic}) {
    const SlabProblem p = ground_problem(1.0, 0.9, 0.6, src);
    PnOptions o;
    o.order = 127;
    o.boundary = PnBoundary::mark;
    const double e = largest_rel(solve_slab_pn(p, o).values, solve_slab_doubling(p));
    INFO("beam " << (src == SlabSource::beam) << ": " << e);
    CHECK(e <= PnGroundTolerances::mark_p127);
  }
}

TEST_CASE("P_N with a white ground and no absorption reflects all the light", "[pn][ground]") {
  // omega = 1, A = 1: nothing is absorbed, so the flux up at the top is the incident flux pi.
  // Marshak's first bottom row makes the upward flux at the ground A times the downward one, so
  // P_N conserves this exactly, at every order.
  for (int N : {1, 7, 31})
    for (double tau : {0.03125, 1.0, 100.0})
      for (SlabSource src : {SlabSource::beam, SlabSource::isotropic}) {
        SlabProblem p = ground_problem(tau, 1.0, 1.0, src);
        PnOptions o;
        o.order = N;
        const PnSolution s = solve_slab_pn(p, o);
        INFO("N " << N << " tau " << tau);
        CHECK(rel(s.values.flux_up_top, kPi) <= PnGroundTolerances::energy_rel);
      }
}

TEST_CASE("the doubling's ground agrees with the Monte Carlo that reflects photons at the ground", "[pn][ground]") {
  // Analog Monte Carlo, 2^18 photons, seed 7: each value within 4 standard errors plus the
  // doubling's own error (<= 5e-8 relative, slab_doubling.hpp) of the doubling.
  for (double A : {0.3, 1.0})
    for (double tau : {0.25, 4.0}) {
      SlabProblem p = ground_problem(tau, 0.9, A, SlabSource::beam);
      const SlabValues ref = solve_slab_doubling(p);
      SlabMonteCarloOptions mc;
      mc.photons = 1 << 18;
      mc.seed = 7;
      const SlabEstimates e = solve_slab_monte_carlo(p, mc);
      auto near = [](const Estimate& x, double r) { return std::fabs(x.mean - r) <= 4 * x.std_error + 5e-8 * std::fabs(r); };
      INFO("A " << A << " tau " << tau);
      CHECK(near(e.flux_up_top, ref.flux_up_top));
      CHECK(near(e.diffuse_down_bottom, ref.diffuse_down_bottom));
      for (std::size_t i = 0; i < 3; ++i) {
        INFO("mu " << p.mu_up[i]);
        CHECK(near(e.intensity_up_top[i], ref.intensity_up_top[i]));
        CHECK(near(e.intensity_down_bottom[i], ref.intensity_down_bottom[i]));
      }
      // And on the thinner slab the ground changes the answer by far more than that noise (the
      // agreement is not that of two answers blind to the ground).
      SlabProblem black = p;
      black.ground_albedo = 0;
      if (tau < 1)
        CHECK(std::fabs(solve_slab_doubling(black).flux_up_top - ref.flux_up_top) > 10 * e.flux_up_top.std_error);
    }
}

TEST_CASE("rayint slab --ground-albedo and a scene's ground reach every solver", "[pn][ground][cli]") {
  rayint::test::TempDir dir;
  const auto run = rayint::test::run_cli(
      dir.path, "slab --tau 1 --albedo 0.9 --mu0 0.5 --mu-up 1 --ground-albedo 0.4 --method doubling,pn:order=63");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const auto j = nlohmann::json::parse(run.out);
  CHECK(j["ground_albedo"] == 0.4);
  CHECK_FALSE(j.contains("integral_equation"));  // black ground only
  const double d = j["doubling"]["flux_up_top"], pn = j["pn"]["flux_up_top"];
  CHECK(rel(pn, d) <= PnGroundTolerances::p31);
  // The scene form: "ground": {"type": "lambertian", "albedo": A}.
  const std::string scene = R"({"name": "g", "medium": {"type": "slab", "optical_thickness": 1, "albedo": 0.9},
    "phase": {"type": "isotropic"}, "lights": [{"type": "beam", "mu0": 0.5}],
    "detectors": {"mu_up": [1]}, "ground": {"type": "lambertian", "albedo": 0.4}})";
  write_text(dir.path / "g.json", scene);
  const auto sc = rayint::test::run_cli(dir.path, "slab --scene g.json --method doubling,pn:order=63");
  INFO(sc.err);
  REQUIRE(sc.status == 0);
  const auto sj = nlohmann::json::parse(sc.out);
  CHECK(sj["doubling"]["flux_up_top"] == j["doubling"]["flux_up_top"]);
  // Bad grounds: one line naming the field, exit 2.
  for (const std::string bad : {R"("ground": {"type": "specular", "albedo": 0.4})", R"("ground": {"type": "lambertian", "albedo": 1.5})",
                                R"("ground": {"type": "lambertian"})", R"("ground": {"type": "lambertian", "albedo": 0.4, "x": 1})"}) {
    std::string text = scene;
    text.replace(text.find("\"ground\""), std::string::npos, bad + "}");
    write_text(dir.path / "bad.json", text);
    const auto r = rayint::test::run_cli(dir.path, "slab --scene bad.json --method pn");
    INFO(bad << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("ground") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
  }
  const auto neg = rayint::test::run_cli(dir.path, "slab --tau 1 --ground-albedo -0.1 --method pn");
  CHECK(neg.status == 2);
  CHECK(neg.err.find("--ground-albedo") != std::string::npos);
}
