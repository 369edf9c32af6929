// P_N for the plane-parallel slab (src/rayint/scattering/pn.hpp) against: its own P1 closed form
// derived by hand (conservative isotropic slab), energy conservation, the adding-doubling solver
// (an independent method, itself within 5e-8 of the integral equation on DISORT 1a-1f), the
// published DISORT values, thick slabs and the CLI. Bounds: tests/tolerances.hpp, PnTolerances.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/core/math.hpp"
#include "rayint/input/slab_benchmark_reader.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/scattering/pn.hpp"
#include "rayint/scattering/slab_doubling.hpp"
#include "scatter_fixtures.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::PnTolerances;

namespace {

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// Every value of a solution as (label, value): fluxes, then intensities.
std::map<std::string, double> labelled(const SlabProblem& p, const SlabValues& v) {
  std::map<std::string, double> m{{"flux_up_top", v.flux_up_top}, {"diffuse_down_bottom", v.diffuse_down_bottom}};
  for (std::size_t i = 0; i < p.mu_up.size(); ++i)
    m["intensity_up_top(" + std::to_string(p.mu_up[i]) + ")"] = v.intensity_up_top[i];
  for (std::size_t i = 0; i < p.mu_down.size(); ++i)
    m["intensity_down_bottom(" + std::to_string(p.mu_down[i]) + ")"] = v.intensity_down_bottom[i];
  return m;
}

double largest_rel(const std::map<std::string, double>& a, const std::map<std::string, double>& ref) {
  double e = 0;
  for (const auto& [k, v] : ref) e = std::max(e, rel(a.at(k), v));
  return e;
}

std::string benchmark_path() { return std::string(RAYINT_SOURCE_DIR) + "/cases/scattering/disort_slab.json"; }

// The DISORT problems with detectors at 0.1, 0.5, 1 both ways.
std::vector<BenchmarkProblem> disort_problems() {
  std::vector<BenchmarkProblem> out = read_slab_benchmark(benchmark_path()).problems;
  for (auto& b : out) {
    b.problem.mu_up = {0.1, 0.5, 1.0};
    b.problem.mu_down = {0.1, 0.5, 1.0};
  }
  return out;
}

}  // namespace

TEST_CASE("P1 equals its hand-derived closed form on a conservative isotropic slab", "[pn]") {
  // P1, omega = 1, isotropic, beam mu0 (F0 = pi/mu0), Marshak: I = a0 + a1 mu with
  //   a1'/3 = e^{-t/mu0}/(4 mu0),  a0' = -a1  =>  a1 = A - c e^{-t/mu0},  a0 = B - A t - c mu0 e^{-t/mu0},
  // c = 3/4; a0/2 + a1/3 = 0 at t = 0 and a0/2 - a1/3 = 0 at t = tau give
  //   A = (c mu0 (1 - E)/2 + c (1 + E)/3) / (tau/2 + 2/3),  E = e^{-tau/mu0},
  //   F_up(0) = 2 pi (a0/2 - a1/3) = (4 pi/3)(c - A),   F_down(tau) = (4 pi/3)(A - c E).
  for (double tau : {0.03125, 1.0, 10.0, 1000.0})
    for (double mu0 : {0.1, 0.5, 1.0}) {
      SlabProblem p;
      p.tau = tau;
      p.albedo = 1;
      p.mu0 = mu0;
      PnOptions o;
      o.order = 1;
      const PnSolution s = solve_slab_pn(p, o);
      const double c = 0.75, E = std::exp(-tau / mu0);
      const double A = (c * mu0 * (1 - E) / 2 + c * (1 + E) / 3) / (tau / 2 + 2.0 / 3);
      INFO("tau " << tau << " mu0 " << mu0);
      CHECK(rel(s.values.flux_up_top, 4 * kPi / 3 * (c - A)) <= PnTolerances::p1_closed_form_rel);
      CHECK(rel(s.values.diffuse_down_bottom, 4 * kPi / 3 * (A - c * E)) <= PnTolerances::p1_closed_form_rel);
      CHECK(s.diagnostics.conservative);
    }
}

TEST_CASE("P_N conserves energy at albedo 1 with Marshak boundary conditions", "[pn]") {
  // Marshak's i = 1 condition makes the half-range fluxes at the faces exact moments of the
  // solution, and the l = 0 equation conserves the net flux, so F_up + F_down + direct = pi.
  for (int N : {1, 3, 15, 31, 127})
    for (double g : {0.0, 0.75})
      for (auto source : {SlabSource::beam, SlabSource::isotropic})
        for (double tau : {0.03125, 1.0, 32.0, 1e4}) {
          SlabProblem p;
          p.tau = tau;
          p.albedo = 1;
          p.mu0 = 0.3;
          p.source = source;
          p.phase = g == 0 ? PhaseFunction::isotropic() : PhaseFunction::henyey_greenstein(g);
          PnOptions o;
          o.order = N;
          const SlabValues v = solve_slab_pn(p, o).values;
          INFO("N " << N << " g " << g << " tau " << tau);
          CHECK(std::fabs(v.flux_up_top + v.diffuse_down_bottom + v.direct_down_bottom - kPi) <=
                PnTolerances::energy_rel * kPi);
        }
}

TEST_CASE("P_N converges to the doubling on the DISORT problems", "[pn]") {
  // Largest relative error over flux_up_top, diffuse_down_bottom and the intensities at
  // mu = 0.1, 0.5, 1 both ways (source-function integration), Marshak.
  for (const BenchmarkProblem& b : disort_problems()) {
    const SlabValues ref = solve_slab_doubling(b.problem);
    const auto r = labelled(b.problem, ref);
    std::vector<double> err;
    for (int N : {15, 31, 63, 127}) {
      PnOptions o;
      o.order = N;
      err.push_back(largest_rel(labelled(b.problem, solve_slab_pn(b.problem, o).values), r));
    }
    INFO(b.id << ": P15 " << err[0] << " P31 " << err[1] << " P63 " << err[2] << " P127 " << err[3]);
    const PnTolerances::Problem& t = PnTolerances::problem(b.id);
    CHECK(err[1] <= t.p31);
    CHECK(err[3] <= t.p127);
    // The measured trend: every doubling of N + 1 divides the error by >= 2.5 (observed order
    // ~2, pn.hpp), so a solver that stalls fails here even below the bounds.
    for (std::size_t k = 1; k < err.size(); ++k) CHECK(err[k] * PnTolerances::min_gain_per_doubling <= err[k - 1]);
  }
}

TEST_CASE("P_N source-function intensities beat the truncated series", "[pn]") {
  // The reason for the source-function integration: on the forward-peaked 3a the series at P31
  // is off by far more than the integrated intensities.
  const auto problems = disort_problems();
  const auto it = std::find_if(problems.begin(), problems.end(), [](const BenchmarkProblem& x) { return x.id == "3a"; });
  REQUIRE(it != problems.end());
  const BenchmarkProblem& b = *it;
  const SlabValues ref = solve_slab_doubling(b.problem);
  PnOptions o;
  o.order = 31;
  const PnSolution s = solve_slab_pn(b.problem, o);
  double e_sfi = 0, e_series = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    e_sfi = std::max({e_sfi, rel(s.values.intensity_up_top[i], ref.intensity_up_top[i]),
                      rel(s.values.intensity_down_bottom[i], ref.intensity_down_bottom[i])});
    e_series = std::max({e_series, rel(s.series_up_top[i], ref.intensity_up_top[i]),
                         rel(s.series_down_bottom[i], ref.intensity_down_bottom[i])});
  }
  INFO("SFI " << e_sfi << " series " << e_series);
  CHECK(e_series >= PnTolerances::series_over_sfi_3a * e_sfi);
}

TEST_CASE("P_N against the published DISORT values", "[pn]") {
  // At P127 every published value is matched as well as the doubling matches it (the published
  // values are off by up to 1.1e-2 on 3a, reports/scattering/README.md), plus P127's own error.
  for (const BenchmarkProblem& b : disort_problems()) {
    const SlabValues ref = solve_slab_doubling(b.problem);
    PnOptions o;
    o.order = 127;
    const SlabValues v = solve_slab_pn(b.problem, o).values;
    for (const BenchmarkValue& x : b.values) {
      auto pick = [&](const SlabValues& s) {
        switch (x.quantity) {
          case SlabQuantity::flux_up_top: return s.flux_up_top;
          case SlabQuantity::diffuse_down_bottom: return s.diffuse_down_bottom;
          case SlabQuantity::direct_down_bottom: return s.direct_down_bottom;
          case SlabQuantity::intensity_up_top: {
            const auto i = static_cast<std::size_t>(std::find(b.problem.mu_up.begin(), b.problem.mu_up.end(), x.mu) - b.problem.mu_up.begin());
            return s.intensity_up_top.at(i);
          }
          case SlabQuantity::intensity_down_bottom: {
            const auto i = static_cast<std::size_t>(std::find(b.problem.mu_down.begin(), b.problem.mu_down.end(), x.mu) - b.problem.mu_down.begin());
            return s.intensity_down_bottom.at(i);
          }
        }
        return 0.0;
      };
      INFO(b.id << " " << x.label() << " published " << x.published << " pn " << pick(v) << " doubling " << pick(ref));
      CHECK(rel(pick(v), x.published) <=
            std::max(x.tolerance_rel, rel(pick(ref), x.published)) + PnTolerances::problem(b.id).p127);
    }
  }
}

TEST_CASE("P_N on thick slabs is finite and agrees with the doubling", "[pn]") {
  for (double albedo : {0.9, 1.0})
    for (double g : {0.0, 0.75}) {
      SlabProblem p;
      p.tau = 1000;
      p.albedo = albedo;
      p.mu0 = 0.5;
      p.phase = g == 0 ? PhaseFunction::isotropic() : PhaseFunction::henyey_greenstein(g);
      p.mu_up = {0.1, 0.5, 1.0};
      p.mu_down = {1.0};
      PnOptions o;
      o.order = 63;
      const PnSolution s = solve_slab_pn(p, o);
      const SlabValues ref = solve_slab_doubling(p);
      INFO("albedo " << albedo << " g " << g << " rcond " << s.diagnostics.rcond);
      CHECK(rel(s.values.flux_up_top, ref.flux_up_top) <= PnTolerances::thick_rel);
      for (std::size_t i = 0; i < 3; ++i)
        CHECK(rel(s.values.intensity_up_top[i], ref.intensity_up_top[i]) <= PnTolerances::thick_rel);
      if (albedo == 1) {  // diffuse transmission ~ 1/tau, still resolved
        CHECK(rel(s.values.diffuse_down_bottom, ref.diffuse_down_bottom) <= PnTolerances::thick_rel);
      }
      // tau = 1e4 and 1e6: finite; with absorption the reflection is that of the semi-infinite
      // slab already at 1000 (e^{-kappa_min 1000} underflows).
      for (double tau : {1e4, 1e6}) {
        p.tau = tau;
        const PnSolution t = solve_slab_pn(p, o);
        CHECK(std::isfinite(t.values.flux_up_top));
        if (albedo < 1) {
          CHECK(t.values.flux_up_top == Approx(s.values.flux_up_top).epsilon(1e-13));
          CHECK(t.values.intensity_up_top[0] == Approx(s.values.intensity_up_top[0]).epsilon(1e-13));
        } else {
          CHECK(t.values.diffuse_down_bottom > 0);
          CHECK(t.values.diffuse_down_bottom < s.values.diffuse_down_bottom);
        }
      }
    }
}

TEST_CASE("P_N with Mark's boundary conditions converges to the doubling too", "[pn]") {
  const auto problems = disort_problems();
  for (const BenchmarkProblem& b : problems) {
    if (b.id != "1e" && b.id != "3a") continue;
    const auto r = labelled(b.problem, solve_slab_doubling(b.problem));
    PnOptions o;
    o.boundary = PnBoundary::mark;
    o.order = 31;
    const double e31 = largest_rel(labelled(b.problem, solve_slab_pn(b.problem, o).values), r);
    o.order = 127;
    const double e127 = largest_rel(labelled(b.problem, solve_slab_pn(b.problem, o).values), r);
    INFO(b.id << " Mark: P31 " << e31 << " P127 " << e127);
    CHECK(e127 <= PnTolerances::mark_p127);
    CHECK(e127 * PnTolerances::min_gain_per_doubling * PnTolerances::min_gain_per_doubling <= e31);
  }
}

TEST_CASE("P_N: a tabulated phase function as Legendre coefficients", "[pn]") {
  // A table g^l (long enough that g^L is below rounding) is Henyey-Greenstein: same solution.
  SlabProblem p = test::hg_slab(0.75);
  PnOptions o;
  o.order = 15;
  const PnSolution hg = solve_slab_pn(p, o);
  for (int l = 0; l <= 160; ++l) o.legendre.push_back(std::pow(0.75, l));
  const PnSolution tab = solve_slab_pn(p, o);
  CHECK(rel(tab.values.flux_up_top, hg.values.flux_up_top) <= 1e-13);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(rel(tab.values.intensity_up_top[i], hg.values.intensity_up_top[i]) <= 1e-12);
    CHECK(rel(tab.values.intensity_down_bottom[i], hg.values.intensity_down_bottom[i]) <= 1e-12);
  }
  // The Lambert sphere's coefficients by quadrature: chi_1 is its mean cosine -4/9.
  const std::vector<double> chi = phase_legendre_coefficients(PhaseFunction::lambert_sphere(), 8);
  CHECK(chi[0] == Approx(1).epsilon(1e-12));
  CHECK(chi[1] == Approx(-4.0 / 9).epsilon(1e-9));
  // Bad tables and orders are refused.
  o.legendre = {0.9, 0.5};
  CHECK_THROWS_AS(solve_slab_pn(p, o), std::invalid_argument);
  o.legendre = {1, 1.0};
  CHECK_THROWS_AS(solve_slab_pn(p, o), std::invalid_argument);
  o.legendre.clear();
  for (int N : {0, 2, -1, kPnMaxOrder + 2}) {
    o.order = N;
    CHECK_THROWS_AS(solve_slab_pn(p, o), std::invalid_argument);
  }
}

TEST_CASE("P_N at a beam resonance 1/mu0 = kappa averages two nearby solves", "[pn]") {
  // P1, isotropic, omega 0.5: kappa^2 = 3 (1 - omega) = 1.5; mu0 = 1/kappa makes (B - A/mu0)
  // singular. The field is smooth in mu0, so the resonant value lies between its neighbours.
  SlabProblem p;
  p.tau = 2;
  p.albedo = 0.5;
  p.mu_up = {0.5};
  PnOptions o;
  o.order = 1;
  p.mu0 = 1 / std::sqrt(1.5);
  const PnSolution at = solve_slab_pn(p, o);
  CHECK(at.diagnostics.resonance_averaged);
  const double h = 1e-3;
  p.mu0 = (1 + h) / std::sqrt(1.5);
  const PnSolution hi = solve_slab_pn(p, o);
  p.mu0 = (1 - h) / std::sqrt(1.5);
  const PnSolution lo = solve_slab_pn(p, o);
  CHECK_FALSE(hi.diagnostics.resonance_averaged);
  // Second difference: |f(x) - (f(x+h) + f(x-h))/2| ~ h^2 f''/2; measured 5.6e-8 relative.
  CHECK(rel(at.values.flux_up_top, 0.5 * (hi.values.flux_up_top + lo.values.flux_up_top)) <= PnTolerances::resonance_rel);
  CHECK(rel(at.values.intensity_up_top[0], 0.5 * (hi.values.intensity_up_top[0] + lo.values.intensity_up_top[0])) <=
        PnTolerances::resonance_rel);
}

TEST_CASE("rayint slab --method pn: results under pn, P1 named the diffusion approximation", "[pn][cli]") {
  rayint::test::TempDir dir;
  const auto run = rayint::test::run_cli(
      dir.path, "slab --tau 1 --albedo 0.9 --phase hg:0.5 --mu0 0.5 --mu-up 0.5,1 --mu-down 1 "
                "--method doubling,pn:order=1 -o out.json");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const auto j = nlohmann::json::parse(rayint::test::slurp(dir.path / "out.json"));
  REQUIRE(j.contains("pn"));
  REQUIRE(j.contains("doubling"));
  for (const char* key : {"flux_up_top", "diffuse_down_bottom", "direct_down_bottom", "intensity_up_top",
                          "intensity_down_bottom"})
    CHECK(j["pn"].contains(key));
  CHECK(j["pn"]["intensity_up_top"].size() == 2);
  CHECK(j["pn"]["order"] == 1);
  CHECK(j["pn"]["boundary"] == "marshak");
  CHECK(j["pn"]["label"].get<std::string>().find("diffusion") != std::string::npos);
  const auto mark = rayint::test::run_cli(dir.path, "slab --tau 1 --method pn:order=7:bc=mark");
  REQUIRE(mark.status == 0);
  const auto m = nlohmann::json::parse(mark.out);
  CHECK(m["pn"]["boundary"] == "mark");
  CHECK(m["pn"]["label"] == "P7");
  CHECK_FALSE(m.contains("doubling"));
  // A slab scene solved by P_N: the scene's detectors, under "pn".
  const auto scene = rayint::test::run_cli(
      dir.path, "slab --scene '" + std::string(RAYINT_SOURCE_DIR) + "/cases/scenes/slab-disort-1b.json' --method pn:order=15");
  INFO(scene.err);
  REQUIRE(scene.status == 0);
  const auto sj = nlohmann::json::parse(scene.out);
  CHECK(sj["pn"]["intensity_up_top"].size() == 3);
  CHECK(sj["pn"]["diagnostics"]["conservative"] == true);
}

TEST_CASE("rayint slab --method pn: a bad order or parameter is one line and exit 2", "[pn][cli]") {
  rayint::test::TempDir dir;
  for (const std::string spec : {"pn:order=4", "pn:order=0", "pn:order=129", "pn:order=x", "pn:order=",
                                 "pn:order=3.0", "pn:bc=vacuum", "pn:n=3", "doubling:order=3", "pm"}) {
    const auto run = rayint::test::run_cli(dir.path, "slab --tau 1 --method " + spec + " -o out.json");
    INFO(spec << ": " << run.err);
    CHECK(run.status == 2);
    CHECK(run.out.empty());
    CHECK(rayint::test::line_count(run.err) == 1);
    CHECK(run.err.find("--method") != std::string::npos);
    CHECK(!rayint::test::fs::exists(dir.path / "out.json"));
  }
  const auto bench = rayint::test::run_cli(
      dir.path, "slab --benchmark '" + benchmark_path() + "' --method pn -o out.json");
  CHECK(bench.status == 2);
  CHECK(rayint::test::line_count(bench.err) == 1);
}
