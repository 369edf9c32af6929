// Plane-parallel slab multiple scattering (src/rayint/scattering/): quadrature and the
// azimuthally averaged phase function, single-scattering closed forms against both solvers,
// energy conservation of the doubling method, reproducibility of the Monte Carlo over threads,
// the DISORT benchmark (cases/scattering/disort_slab.json) against both solvers, and the
// `rayint slab` command. Monte Carlo checks use the rule of slab_benchmark.hpp:
// |MC - expected| <= 4 SE, with 4 SE small enough (stated per check) that a biased estimator
// cannot pass by having a wide interval; seeds are fixed, so outcomes are reproducible.
#include <algorithm>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/special/gauss_legendre.hpp"
#include "rayint/input/slab_benchmark_reader.hpp"
#include "rayint/scattering/slab_benchmark.hpp"
#include "rayint/scattering/slab_doubling.hpp"
#include "rayint/scattering/slab_integral_equation.hpp"
#include "rayint/scattering/slab_monte_carlo.hpp"
#include "rayint/scattering/slab_single_scattering.hpp"
#include "tolerances.hpp"

using namespace rayint;
using Tolerances = rayint::test::ScatterTolerances;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

std::string benchmark_path() {
  return std::string(RAYINT_SOURCE_DIR) + "/cases/scattering/disort_slab.json";
}

// |estimate - expected| <= 4 SE, and 4 SE <= max_rel |expected| (so the check has teeth);
// 4 = Tolerances::mc_se_multiple.
void check_mc(const Estimate& e, double expected, double max_rel, const std::string& what) {
  INFO(what << ": MC " << e.mean << " +- " << e.std_error << " (n = " << e.samples
            << "), expected " << expected);
  CHECK(std::fabs(e.mean - expected) <= Tolerances::mc_se_multiple * e.std_error);
  CHECK(Tolerances::mc_se_multiple * e.std_error <= max_rel * std::fabs(expected));
}

}  // namespace

TEST_CASE("Gauss-Legendre on [0, 1] integrates x^(2n-1) exactly", "[scatter]") {
  for (int n : {1, 2, 5, 16, 64, 128}) {
    const GaussLegendre q = gauss_legendre_01(n);
    double sum_w = 0, moment = 0;
    for (std::size_t i = 0; i < q.nodes.size(); ++i) {
      sum_w += q.weights[i];
      moment += q.weights[i] * std::pow(q.nodes[i], 2 * n - 1);
    }
    INFO("n = " << n);
    CHECK(std::fabs(sum_w - 1) <= Tolerances::gauss_weight_sum_abs);
    CHECK(rel(moment, 1.0 / (2 * n)) <= Tolerances::gauss_moment_rel);
  }
}

TEST_CASE("azimuthally averaged phase function against the trapezoid rule", "[scatter]") {
  const double mus[] = {-1, -0.9, -0.5, -0.1, 0, 0.1, 0.3, 0.5, 0.9, 1};
  for (const PhaseFunction& p :
       {PhaseFunction::isotropic(), PhaseFunction::henyey_greenstein(0.75),
        PhaseFunction::henyey_greenstein(-0.4), PhaseFunction::henyey_greenstein(0.2)}) {
    for (double a : mus)
      for (double b : mus) {
        INFO(p.name() << " g " << p.g() << " mu_a " << a << " mu_b " << b);
        CHECK(rel(azimuthal_phase(p, a, b), azimuthal_phase_trapezoid(p, a, b, 4096)) <=
              Tolerances::azimuthal_phase_rel);
      }
  }
  // Lambert sphere: 512-node trapezoid against 8192 nodes (header claim: <= 1e-7; the bound is
  // Tolerances::lambert_phase_abs in units of the isotropic level).
  const PhaseFunction lambert = PhaseFunction::lambert_sphere();
  for (double a : mus)
    for (double b : mus) {
      INFO("lambert mu_a " << a << " mu_b " << b);
      // Absolute against the isotropic level 1/(4 pi): p vanishes in the forward direction.
      CHECK(std::fabs(azimuthal_phase(lambert, a, b) - azimuthal_phase_trapezoid(lambert, a, b, 8192)) <=
            Tolerances::lambert_phase_abs / (4 * kPi));
    }
}

TEST_CASE("single-scattering closed form: transmitted limit at mu = mu0", "[scatter]") {
  SlabProblem p;
  p.tau = 0.7;
  p.albedo = 0.9;
  p.mu0 = 0.6;
  p.phase = PhaseFunction::henyey_greenstein(0.5);
  const double at = single_scattering_transmitted(p, 0.6);
  // The mu = mu0 form, written out: omega F0 p0 tau / mu0^2 exp(-tau/mu0).
  const double expected =
      p.albedo * kPi * azimuthal_phase(p.phase, 0.6, 0.6) * p.tau / (0.36) * std::exp(-p.tau / 0.6);
  CHECK(rel(at, expected) <= Tolerances::single_closed_form_rel);
  for (double d : {1e-4, 1e-7, 1e-10}) {
    INFO("mu - mu0 = " << d);
    CHECK(rel(single_scattering_transmitted(p, 0.6 + d), at) <=
          Tolerances::single_limit_slope * d + Tolerances::single_limit_floor);
    CHECK(rel(single_scattering_transmitted(p, 0.6 - d), at) <=
          Tolerances::single_limit_slope * d + Tolerances::single_limit_floor);
  }
  // Reflected form written out at one point.
  const double mu = 0.3;
  const double r = p.albedo * kPi * azimuthal_phase(p.phase, mu, -p.mu0) / (mu + p.mu0) *
                   (1 - std::exp(-p.tau * (1 / mu + 1 / p.mu0)));
  CHECK(rel(single_scattering_reflected(p, mu), r) <= Tolerances::single_closed_form_rel);
}

TEST_CASE("doubling at tiny albedo reduces to the single-scattering closed forms", "[scatter]") {
  for (const PhaseFunction& ph : {PhaseFunction::isotropic(), PhaseFunction::henyey_greenstein(0.75)})
    for (double tau : {0.03125, 1.0, 8.0}) {
      // (tau 8: transmission at grazing mu is dominated by second order even at omega 1e-6 --
      // scattered toward mu ~ 1, crossing, scattered back to mu = 0.1 beats exp(-80) -- so
      // only the reflection is compared there.)
      const bool compare_transmission = tau <= 1;
      SlabProblem p;
      p.tau = tau;
      p.albedo = 1e-6;  // multiple scattering O(omega^2): 1e-6 of the single-scattering part
      p.phase = ph;
      p.mu0 = 0.3;
      p.mu_up = {0.1, 0.3, 0.5, 1.0};
      p.mu_down = {0.1, 0.3, 0.5, 1.0};
      const SlabValues d = solve_slab_doubling(p);
      const SlabValues s = single_scattering(p);
      INFO(ph.name() << " tau " << tau);
      for (std::size_t i = 0; i < p.mu_up.size(); ++i) {
        INFO("mu " << p.mu_up[i]);
        CHECK(rel(d.intensity_up_top[i], s.intensity_up_top[i]) <= Tolerances::slab_single_rel);
        if (compare_transmission)
          CHECK(rel(d.intensity_down_bottom[i], s.intensity_down_bottom[i]) <=
                Tolerances::slab_single_rel);
      }
      CHECK(rel(d.flux_up_top, s.flux_up_top) <= Tolerances::slab_single_rel);
      if (compare_transmission)
        CHECK(rel(d.diffuse_down_bottom, s.diffuse_down_bottom) <= Tolerances::slab_single_rel);
    }
}

TEST_CASE("doubling conserves energy without absorption", "[scatter]") {
  // flux_up + diffuse_down + direct_down = pi for omega = 1 (the incident flux): a check of the
  // start layer and of every doubling step (a start layer too thin loses digits to the rounding
  // of exp(-t0/mu) and breaks it at the 1e-3 level; see slab_doubling.hpp).
  for (const PhaseFunction& ph : {PhaseFunction::isotropic(), PhaseFunction::henyey_greenstein(0.75)})
    for (double tau : {0.03125, 1.0, 32.0})
      for (int streams : {32, 64, 128}) {
        SlabProblem p;
        p.tau = tau;
        p.albedo = 1;
        p.phase = ph;
        p.mu0 = 0.4;
        DoublingOptions o;
        o.streams = streams;
        const SlabValues v = solve_slab_doubling(p, o);
        INFO(ph.name() << " tau " << tau << " streams " << streams);
        const double beam_err = std::fabs(v.flux_up_top + v.diffuse_down_bottom + v.direct_down_bottom - kPi);
        CHECK(beam_err <= Tolerances::slab_energy_abs);
        p.source = SlabSource::isotropic;
        const SlabValues w = solve_slab_doubling(p, o);
        const double iso_err = std::fabs(w.flux_up_top + w.diffuse_down_bottom - kPi);
        CHECK(iso_err <= Tolerances::slab_energy_abs);
      }
}

TEST_CASE("Monte Carlo truncated to single scattering matches the closed forms", "[scatter]") {
  for (const PhaseFunction& ph : {PhaseFunction::isotropic(), PhaseFunction::henyey_greenstein(0.75)}) {
    SlabProblem p;
    p.tau = 0.5;
    p.albedo = 0.8;
    p.phase = ph;
    p.mu0 = 0.5;
    p.mu_up = {0.1, 0.5, 1.0};
    p.mu_down = {0.1, 0.5, 1.0};  // 0.5 = mu0: the limit form
    SlabMonteCarloOptions o;
    o.photons = 400000;
    o.seed = 11;
    o.max_order = 1;
    const SlabEstimates e = solve_slab_monte_carlo(p, o);
    const SlabValues s = single_scattering(p);
    const std::string name = ph.name();
    const double max_rel = Tolerances::slab_mc_single_max_rel;
    for (std::size_t i = 0; i < p.mu_up.size(); ++i) {
      check_mc(e.intensity_up_top[i], s.intensity_up_top[i], max_rel, name + " up mu " + std::to_string(p.mu_up[i]));
      check_mc(e.intensity_down_bottom[i], s.intensity_down_bottom[i], max_rel,
               name + " down mu " + std::to_string(p.mu_down[i]));
    }
    check_mc(e.flux_up_top, s.flux_up_top, max_rel, name + " flux up");
    check_mc(e.diffuse_down_bottom, s.diffuse_down_bottom, max_rel, name + " diffuse down");
    check_mc(e.direct_down_bottom, s.direct_down_bottom, max_rel, name + " direct down");
  }
}

TEST_CASE("Monte Carlo results do not depend on the thread count", "[scatter]") {
  SlabProblem p;
  p.tau = 2;
  p.albedo = 0.9;
  p.phase = PhaseFunction::henyey_greenstein(0.5);
  p.mu0 = 0.7;
  p.mu_up = {0.2, 0.9};
  SlabMonteCarloOptions o;
  o.photons = 50000;
  o.seed = 5;
  o.threads = 1;
  const SlabEstimates a = solve_slab_monte_carlo(p, o);
  o.threads = 3;
  const SlabEstimates b = solve_slab_monte_carlo(p, o);
  CHECK(a.flux_up_top.mean == b.flux_up_top.mean);
  CHECK(a.flux_up_top.std_error == b.flux_up_top.std_error);
  CHECK(a.intensity_up_top[1].mean == b.intensity_up_top[1].mean);
  CHECK(a.collisions == b.collisions);
  o.seed = 6;
  const SlabEstimates c = solve_slab_monte_carlo(p, o);
  CHECK(c.flux_up_top.mean != a.flux_up_top.mean);
}

TEST_CASE("DISORT benchmark: doubling holds the published tolerance", "[scatter]") {
  const SlabBenchmark b = read_slab_benchmark(benchmark_path());
  REQUIRE(b.problems.size() == 8);
  BenchmarkRunOptions o;
  o.monte_carlo = false;
  o.integral_equation = false;  // its own test below
  const BenchmarkReport r = run_slab_benchmark(b, o);
  REQUIRE(r.rows.size() == 42);
  int reproduced = 0;
  for (const auto& row : r.rows) {
    const std::string label = row.problem_id + " " + row.value.label();
    INFO(label << ": published " << row.value.published << ", doubling " << row.doubling
               << ", rel dev " << row.doubling_rel_dev);
    // Values not reproduced (tests/tolerances.hpp: the published value is off by the three
    // solvers' verdict, or undecided): pinned at their measured deviation.
    const auto* nr = Tolerances::slab_not_reproduced(label);
    if (nr) {
      CHECK_FALSE(row.doubling_pass);
      CHECK(std::fabs(row.doubling_rel_dev) <= Tolerances::slab_pin_factor * nr->measured_rel_dev);
    } else {
      CHECK(row.doubling_pass);
      ++reproduced;
    }
  }
  CHECK(reproduced == 42 - Tolerances::slab_not_reproduced_count);
}

TEST_CASE("DISORT benchmark: Monte Carlo agrees with doubling and the published values", "[scatter]") {
  // CI budget (seed 3): 60k photons per problem, 400k for 3a (forward-peaked, its intensities
  // converge slowly) and for 1e, 1f (rare transmission through tau 32). 1f's diffuse
  // transmission (1.5e-3 of the incident flux) needs ~6 M photons for 4 SE <= 5%: it is checked
  // in the full run (reports/scattering/), not here.
  SlabBenchmark b = read_slab_benchmark(benchmark_path());
  BenchmarkReport r;
  for (const auto& problem : b.problems) {
    SlabBenchmark one = b;
    one.problems = {problem};
    BenchmarkRunOptions o;
    o.mc_options.photons = (problem.id == "3a" || problem.id == "1e" || problem.id == "1f") ? 400000 : 60000;
    o.mc_options.seed = 3;
    o.mc_max_rel = Tolerances::disort_mc_max_rel;
    const BenchmarkReport part = run_slab_benchmark(one, o);
    r.rows.insert(r.rows.end(), part.rows.begin(), part.rows.end());
  }
  for (const auto& row : r.rows) {
    const std::string label = row.problem_id + " " + row.value.label();
    const Estimate& e = row.monte_carlo;
    if (row.problem_id == "1f" && row.value.quantity == SlabQuantity::diffuse_down_bottom) continue;
    check_mc(e, row.doubling, Tolerances::disort_mc_max_rel, label + " MC vs doubling");
    if (!Tolerances::slab_not_reproduced(label)) {
      INFO(label << " verdict " << row.verdict_name());
      CHECK(row.mc_pass);
    }
  }
}

TEST_CASE("rayint slab --benchmark runs and reports", "[scatter][cli]") {
  rayint::test::TempDir dir;
  const auto run = rayint::test::run_cli(
      dir.path, "slab --benchmark '" + benchmark_path() +
                    "' --problems 1d,3b --photons 20000 --seed 2 --mc-max-rel " +
                    std::to_string(Tolerances::disort_mc_max_rel) + " --quiet --json -o out.json");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const auto j = nlohmann::json::parse(rayint::test::slurp(dir.path / "out.json"));
  CHECK(j["all_pass"] == true);
  CHECK(j["rows"].size() == 7);
  // Doubling alone on the whole file: the disputed values cannot be told from failures -> exit 1.
  const auto all = rayint::test::run_cli(
      dir.path, "slab --benchmark '" + benchmark_path() + "' --method doubling --quiet");
  CHECK(all.status == 1);
  CHECK(all.out.find("reproduced") != std::string::npos);
}

TEST_CASE("rayint slab: bad input is one line and exit 2", "[scatter][cli]") {
  rayint::test::TempDir dir;
  struct Bad {
    std::string text, expect;
  };
  const Bad bad[] = {
      {R"({"isotropic": [{"id": "x", "tau": -1, "albedo": 1, "source": "beam", "mu0": 0.5, "flux_up_top": 1}]})",
       "b.json: isotropic[0].tau: "},
      {R"({"isotropic": [{"id": "x", "tau": 1, "albedo": 1.5, "source": "beam", "mu0": 0.5, "flux_up_top": 1}]})",
       "b.json: isotropic[0].albedo: "},
      {R"({"isotropic": [{"id": "x", "tau": 1, "albedo": 1, "source": "sun", "flux_up_top": 1}]})",
       "b.json: isotropic[0].source: "},
      {R"({"isotropic": [{"id": "x", "tau": 1, "albedo": 1, "source": "beam", "mu0": 0.5, "flux": 1}]})",
       "b.json: isotropic[0].flux: "},
      {R"({"isotropic": [{"id": "x", "tau": 1, "albedo": 1, "source": "beam", "mu0": 0.5, "intensity_up_top": {"2": 1}}]})",
       "b.json: isotropic[0].intensity_up_top.2: "},
      {R"({"rayleigh": []})", "b.json: rayleigh: "},
      {R"({"isotropic": []})", "b.json: isotropic: "},
      {R"({"isotropic": [{"id": "x", "tau": 1e999}]})", "b.json: isotropic[0].tau: "},
  };
  for (const auto& b : bad) {
    dir.write("b.json", b.text);
    const auto run = rayint::test::run_cli(dir.path, "slab --benchmark b.json -o out.json --quiet");
    INFO(b.text << "\n" << run.err);
    CHECK(run.status == 2);
    CHECK(run.out.empty());
    CHECK(run.err.rfind("rayint: error: " + b.expect, 0) == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(!fs::exists(dir.path / "out.json"));
  }
  for (const std::string args : {"--tau -1", "--albedo 2", "--phase hg:1", "--mu0 0", "--photons 0",
                                 "--method magic", "--mu-up 0,0.5"}) {
    const auto run = rayint::test::run_cli(dir.path, "slab " + args + " --photons 10 -o out.json");
    INFO(args << ": " << run.err);
    CHECK(run.status == 2);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(!fs::exists(dir.path / "out.json"));
  }
}

TEST_CASE("complete elliptic integral E(k) by the AGM against 50-digit Boost.Math", "[scatter]") {
  using Big = boost::multiprecision::cpp_bin_float_50;
  for (double k2 : {0.0, 1e-12, 1e-6, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.96, 0.99, 0.998, 0.9995, 1.0}) {
    const double k = std::sqrt(k2);
    const double ref = boost::math::ellint_2(Big(k)).convert_to<double>();
    INFO("k^2 = " << k2);
    CHECK(rel(complete_elliptic_e(k), ref) <= Tolerances::elliptic_e_rel);
  }
}

// --- the integral equation for the source function (slab_integral_equation.hpp) ---
namespace {
// Bounds of the integral-equation tests: tests/tolerances.hpp, IntegralEquationTolerances.
using IE = rayint::test::IntegralEquationTolerances;
constexpr double kPiIE = 3.14159265358979323846;

void check_rel(double got, double expected, double tol, const std::string& what) {
  INFO(what << ": got " << got << ", expected " << expected << ", rel " << (got - expected) / expected);
  CHECK(std::fabs(got - expected) <= tol * std::fabs(expected));
}
}  // namespace

TEST_CASE("slab integral equation: first order equals the single-scattering closed forms", "[scatter][ie]") {
  for (SlabSource src : {SlabSource::beam, SlabSource::isotropic}) {
    SlabProblem p;
    p.tau = 0.7;
    p.albedo = 1e-8;
    p.mu0 = 0.4;
    p.source = src;
    p.mu_up = {0.1, 0.4, 1.0};
    p.mu_down = {0.2, 0.4, 1.0};  // 0.4 = mu0: the limit form
    const SlabIntegralEquationResult r = solve_slab_integral_equation(p);
    const SlabValues c = single_scattering(p);
    const std::string name = src == SlabSource::beam ? "beam" : "isotropic";
    for (std::size_t i = 0; i < p.mu_up.size(); ++i)
      check_rel(r.values.intensity_up_top[i], c.intensity_up_top[i], IE::single_rel, name + " up");
    check_rel(r.values.flux_up_top, c.flux_up_top, IE::single_rel, name + " flux up");
    if (src == SlabSource::beam) {  // with isotropic incidence "diffuse down" includes the unscattered light
      for (std::size_t i = 0; i < p.mu_down.size(); ++i)
        check_rel(r.values.intensity_down_bottom[i], c.intensity_down_bottom[i], IE::single_rel, name + " down");
      check_rel(r.values.diffuse_down_bottom, c.diffuse_down_bottom, IE::single_rel, name + " diffuse down");
    }
  }
}

TEST_CASE("slab integral equation: conservative scattering conserves the incident flux", "[scatter][ie]") {
  for (SlabSource src : {SlabSource::beam, SlabSource::isotropic})
    for (double tau : {0.03125, 1.0, 8.0}) {
      SlabProblem p;
      p.tau = tau;
      p.albedo = 1;
      p.mu0 = 0.4;
      p.source = src;
      const SlabIntegralEquationResult r = solve_slab_integral_equation(p);
      const double total = r.values.flux_up_top + r.values.diffuse_down_bottom + r.values.direct_down_bottom;
      const bool beam = src == SlabSource::beam;
      check_rel(total, kPiIE, beam ? IE::energy_beam_rel : IE::energy_isotropic_rel,
                std::string(beam ? "beam" : "isotropic") + " tau " + std::to_string(tau));
      if (!beam)
        for (const SlabValues& m : r.meshes)
          check_rel(m.flux_up_top + m.diffuse_down_bottom, kPiIE, IE::energy_isotropic_rel, "one mesh");
    }
}

TEST_CASE("slab integral equation: second-order convergence and Richardson on DISORT 1a-1c", "[scatter][ie]") {
  const SlabBenchmark b = read_slab_benchmark(benchmark_path());
  for (const auto& bp : b.problems) {
    if (bp.id != "1a" && bp.id != "1b" && bp.id != "1c") continue;
    SlabIntegralEquationOptions fine, coarse;
    coarse.segments = 64;
    const SlabIntegralEquationResult r = solve_slab_integral_equation(bp.problem, fine);
    const SlabIntegralEquationResult q = solve_slab_integral_equation(bp.problem, coarse);
    REQUIRE(r.finest_segments == 1024);
    for (std::size_t i = 0; i < bp.problem.mu_up.size(); ++i) {
      const std::string what = bp.id + " I_up(mu=" + std::to_string(bp.problem.mu_up[i]) + ")";
      INFO(what << " order " << r.observed_order.intensity_up_top[i]);
      CHECK(r.observed_order.intensity_up_top[i] >= IE::order_lo);
      CHECK(r.observed_order.intensity_up_top[i] <= IE::order_hi);
      check_rel(q.values.intensity_up_top[i], r.values.intensity_up_top[i], IE::start_independence_rel, what);
    }
    INFO(bp.id << " flux order " << r.observed_order.flux_up_top);
    CHECK(r.observed_order.flux_up_top >= IE::order_lo);
    CHECK(r.observed_order.flux_up_top <= IE::order_hi);
    check_rel(q.values.flux_up_top, r.values.flux_up_top, IE::start_independence_rel, bp.id + " flux up");
  }
}

TEST_CASE("slab integral equation refuses anisotropic scattering", "[scatter][ie]") {
  SlabProblem p;
  p.phase = PhaseFunction::henyey_greenstein(0.75);
  CHECK_THROWS_AS(solve_slab_integral_equation(p), std::invalid_argument);
}

TEST_CASE("rayint slab --scene: a scene with a slab medium gives the slab results", "[scatter][cli]") {
  // cases/scenes/slab-disort-1b.json declares DISORT problem 1b as a scene; the solvers must see
  // exactly the benchmark's problem (same doubling values to the last bit).
  rayint::test::TempDir dir;
  const std::string scene = std::string(RAYINT_SOURCE_DIR) + "/cases/scenes/slab-disort-1b.json";
  const auto run = rayint::test::run_cli(dir.path, "slab --scene '" + scene + "' --method doubling -o out.json");
  INFO(run.err);
  REQUIRE(run.status == 0);
  const auto j = nlohmann::json::parse(rayint::test::slurp(dir.path / "out.json"));
  const SlabBenchmark b = read_slab_benchmark(benchmark_path());
  SlabProblem p;
  for (const auto& bp : b.problems)
    if (bp.id == "1b") p = bp.problem;
  p.mu_down = {0.1, 0.5, 1.0};
  REQUIRE(p.mu_up == std::vector<double>{0.1, 0.5, 1.0});
  const SlabValues d = solve_slab_doubling(p);
  CHECK(j["doubling"]["flux_up_top"].get<double>() == d.flux_up_top);
  CHECK(j["doubling"]["diffuse_down_bottom"].get<double>() == d.diffuse_down_bottom);
  CHECK(j["doubling"]["direct_down_bottom"].get<double>() == d.direct_down_bottom);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(j["doubling"]["intensity_up_top"][i].get<double>() == d.intensity_up_top[i]);
    CHECK(j["doubling"]["intensity_down_bottom"][i].get<double>() == d.intensity_down_bottom[i]);
  }
  REQUIRE(j.contains("integral_equation"));  // isotropic: the third solver runs too
  CHECK(std::fabs(j["integral_equation"]["intensity_up_top"][0].get<double>() - d.intensity_up_top[0]) <=
        Tolerances::scene_ie_doubling_rel * d.intensity_up_top[0]);
  // A scene medium that is not a slab, an unknown field, two lights: one line, exit 2.
  for (const std::string bad :
       {R"({"name":"x","medium":{"type":"cloud","optical_thickness":1,"albedo":1},"phase":{"type":"isotropic"},"lights":[{"type":"beam","mu0":1}]})",
        R"({"name":"x","medium":{"type":"slab","optical_thickness":1,"albedo":1,"color":1},"phase":{"type":"isotropic"},"lights":[{"type":"beam","mu0":1}]})",
        R"({"name":"x","medium":{"type":"slab","optical_thickness":1,"albedo":1},"phase":{"type":"isotropic"},"lights":[{"type":"beam","mu0":1},{"type":"isotropic"}]})"}) {
    std::ofstream(dir.path / "bad.json") << bad;
    const auto r = rayint::test::run_cli(dir.path, "slab --scene bad.json --method doubling");
    INFO(bad << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}
