// `rayint stress` (src/rayint/studies/stress.hpp, regimes.hpp): reproducible whatever the thread
// count, every regime's samples valid case input within the ranges regimes.hpp states, worst
// samples that replay to the same error, the underflow scoring rule, and the command line's
// handling of bad options. Sizes are small (the million-piece figures come from the command
// itself: reports/stress-exact.json); no test here depends on timing.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rayint/studies/evaluate.hpp"
#include "rayint/generators/regimes.hpp"
#include "rayint/studies/stress.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/case_writer.hpp"
#include "rayint/report/stress_json.hpp"
#include "rayint/model/pieces.hpp"
#include "cli_harness.hpp"
#include "tolerances.hpp"

using namespace rayint;
namespace fs = std::filesystem;

using namespace rayint::test;  // the CLI harness

namespace {

// Every regime but the 10^4-segment long rays (whose reference takes a second or two each).
std::vector<Regime> quick_regimes() {
  std::vector<Regime> out;
  for (const Regime r : stress_regimes())
    if (r != Regime::long_ray) out.push_back(r);
  return out;
}

double optical_depth(const ChannelPiece& p) { return 0.5 * p.length * (p.rho_far + p.rho_exit); }

// Closed interval with a relative slack of a few ulps for the rounding of the sampler's products.
bool in_range(double x, double lo, double hi) {
  const double slack = 8 * std::numeric_limits<double>::epsilon();
  return x >= lo * (1 - slack) && x <= hi * (1 + slack);
}

}  // namespace

TEST_CASE("stress: the same seed gives the same report, whatever the thread count", "[stress]") {
  StressOptions opt;
  opt.count = 900;
  opt.seed = 12345;
  opt.regimes = quick_regimes();
  opt.threads = 1;
  const std::string one = to_json(run_stress(opt)).dump();
  opt.threads = 3;
  const std::string three = to_json(run_stress(opt)).dump();
  const std::string again = to_json(run_stress(opt)).dump();
  CHECK(one == three);
  CHECK(three == again);

  opt.seed = 12346;
  CHECK(to_json(run_stress(opt)).dump() != one);

  // A sample is a function of (seed, regime, index) alone: the same with another count or
  // another set of regimes.
  const RaySample a = stress_sample(7, Regime::narrow_pulse, 3);
  const RaySample b = stress_sample(7, Regime::narrow_pulse, 3);
  CHECK(case_text({"x", "", "", a.transfer, {a.ray}}) == case_text({"x", "", "", b.transfer, {b.ray}}));
  CHECK(sample_seed(7, Regime::thin, 0) != sample_seed(7, Regime::thin, 1));
  CHECK(sample_seed(7, Regime::thin, 0) != sample_seed(7, Regime::thick, 0));
  CHECK(sample_seed(7, Regime::thin, 0) != sample_seed(8, Regime::thin, 0));
}

TEST_CASE("stress: the report counts what it says", "[stress]") {
  StressOptions opt;
  opt.count = 600;
  opt.seed = 3;
  opt.regimes = {Regime::thin, Regime::zero_density, Regime::narrow_pulse, Regime::out_of_range};
  opt.methods = {parse_method_spec("exact"), parse_method_spec("riemann:n=4")};
  const StressReport r = run_stress(opt);
  REQUIRE(r.regimes.size() == 4);
  REQUIRE(r.methods == std::vector<std::string>{"exact", "riemann:n=4"});
  long samples = 0;
  for (const RegimeStress& rs : r.regimes) {
    INFO("regime " << rs.regime);
    samples += rs.samples;
    CHECK(rs.reference_failures == 0);
    CHECK(rs.pieces >= 150);  // 600 split over 4 regimes; ray regimes draw until they reach it
    if (!rs.ray_level) CHECK(rs.samples == 150);
    REQUIRE(rs.methods.size() == 2);
    for (const MethodStress& m : rs.methods) {
      CHECK(m.non_finite == 0);
      CHECK(m.scored + m.underflow >= rs.samples);  // a sample may count in both
      CHECK(m.rel.median <= m.rel.p99);
      CHECK(m.rel.p99 <= m.rel.max);
      CHECK(m.worst.present);
      CHECK(m.worst.replay.name == "stress-" + rs.regime + "-" + (m.method == "exact" ? "exact" : "riemann-n-4"));
    }
    CHECK(rs.methods[0].rel.max <= test::Tolerances::exact_rel);
    if (rs.regime == "zero_density") {
      // rho = 0: the intensity is the background exactly, and 0 (scored absolutely) without one.
      CHECK(rs.methods[0].rel.max == 0.0);
      CHECK(rs.methods[0].underflow > 0);
      CHECK(rs.methods[0].max_abs_error_underflow == 0.0);
      CHECK(rs.methods[0].branches.count("transparent") == 1);
    }
    if (rs.regime == "thin") CHECK(rs.methods[0].branches.count("thin_series") == 1);
  }
  REQUIRE(r.overall.size() == 2);
  CHECK(r.overall[0].scored + r.overall[0].underflow >= samples);
  CHECK(r.overall[0].non_finite == 0);
  CHECK_FALSE(r.overall[0].worst.present);
}

TEST_CASE("stress: every regime's samples are valid case input within the stated ranges",
          "[stress][regimes]") {
  constexpr int kSamples = 400;
  for (const Regime regime : all_regimes()) {
    INFO("regime " << regime_name(regime));
    for (int i = 0; i < kSamples; ++i) {
      std::mt19937_64 rng(sample_seed(99, regime, i));
      const RegimeSample s = sample_piece(regime, rng);
      const ChannelPiece& p = s.piece;
      INFO("sample " << i << " L " << p.length << " rho " << p.rho_far << " -> " << p.rho_exit
                     << " kappa " << p.kappa_far << " -> " << p.kappa_exit << " incoming " << s.incoming);
      for (const double v : {p.length, p.rho_far, p.rho_exit, p.kappa_far, p.kappa_exit, s.incoming}) {
        REQUIRE(std::isfinite(v));
        REQUIRE(v >= 0.0);
      }
      REQUIRE(p.length > 0.0);
      CHECK((s.incoming == 0.0 || in_range(s.incoming, 1e-3, 1e3)));
      const double T = optical_depth(p);
      switch (regime) {
        case Regime::thin: CHECK(in_range(T, 1e-16, 1e-3)); break;
        case Regime::moderate: CHECK(in_range(T, 1e-3, 30.0)); break;
        case Regime::thick: CHECK(in_range(T, 30.0, 1e6)); break;
        case Regime::q2_near_zero_pos:
        case Regime::q2_near_zero_neg: {
          const bool up = regime == Regime::q2_near_zero_pos;
          CHECK((up ? p.rho_exit > p.rho_far : p.rho_exit < p.rho_far));  // never q2 == 0
          const double rel = std::fabs(p.rho_exit - p.rho_far) / (p.rho_exit + p.rho_far);
          CHECK(rel <= 1e-4 * (1 + 1e-9));
          CHECK(in_range(T, 1e-3, 1e3));
          break;
        }
        case Regime::q2_zero:
          CHECK(p.rho_exit == p.rho_far);
          CHECK(p.rho_far > 0.0);
          break;
        case Regime::steep_up: CHECK(in_range(p.rho_exit / p.rho_far, 1e2, 1e12)); break;
        case Regime::steep_down: CHECK(in_range(p.rho_far / p.rho_exit, 1e2, 1e12)); break;
        case Regime::zero_density:
          CHECK(p.rho_far == 0.0);
          CHECK(p.rho_exit == 0.0);
          break;
        case Regime::zero_density_end:
          CHECK(((p.rho_far == 0.0) != (p.rho_exit == 0.0)));
          break;
        case Regime::huge_kappa_tiny_rho:
          CHECK(in_range(p.kappa_far, 1e6, 1e12));
          CHECK(in_range(p.kappa_exit, 1e6, 1e12));
          CHECK(in_range(T, 1e-12, 1e-6));
          break;
        case Regime::extreme_magnitudes:
          CHECK(in_range(p.length, 1e-12, 1e6));
          for (const double v : {p.rho_far, p.rho_exit, p.kappa_far, p.kappa_exit})
            CHECK((v == 0.0 || in_range(v, 1e-12, 1e12)));
          break;
        default: FAIL("not a piece-level regime");
      }
      if (regime != Regime::extreme_magnitudes) CHECK(in_range(p.length, 1e-3, 1e3));

      // As a case: the one-segment ray holds exactly this piece in every channel.
      const RaySample r = piece_as_ray(s);
      const std::vector<Piece> pieces = split_ray(r.transfer, r.ray);
      REQUIRE(pieces.size() == 1);
      for (int c = 0; c < kChannels; ++c) {
        const ChannelPiece q = pieces[0].channel(c);
        CHECK(q.length == p.length);
        CHECK(q.rho_far == p.rho_far);
        CHECK(q.rho_exit == p.rho_exit);
        CHECK(q.kappa_far == p.kappa_far);
        CHECK(q.kappa_exit == p.kappa_exit);
      }
    }
  }

  // The q2 -> 0 regimes reach down to one ulp between the ends (relative slope ~1e-16).
  double smallest = 1.0;
  for (int i = 0; i < 2000; ++i) {
    std::mt19937_64 rng(sample_seed(5, Regime::q2_near_zero_pos, i));
    const ChannelPiece p = sample_piece(Regime::q2_near_zero_pos, rng).piece;
    smallest = std::min(smallest, (p.rho_exit - p.rho_far) / (p.rho_exit + p.rho_far));
  }
  CHECK(smallest < 1e-15);
}

TEST_CASE("stress: ray-level samples are valid case files that visit what their regime is about",
          "[stress][regimes]") {
  for (const Regime regime : stress_regimes()) {
    INFO("regime " << regime_name(regime));
    const int n = regime == Regime::long_ray ? 3 : 300;
    bool narrow_seen = false, ulp_wide_seen = false;
    for (int i = 0; i < n; ++i) {
      INFO("sample " << i);
      const RaySample s = stress_sample(21, regime, i);
      // Written and read back by the strict case reader: valid, and the same doubles.
      const Case c{"sample", "d", "", s.transfer, {s.ray}};
      const std::string text = case_text(c);
      Case back;
      REQUIRE_NOTHROW(back = parse_case_text(text, "sample.json"));
      CHECK(case_text(back) == text);
      for (const Segment& seg : s.ray.segments) REQUIRE(seg.length > 0.0);
      if (!is_ray_regime(regime)) {
        CHECK(s.ray.segments.size() == 1);
        continue;
      }
      switch (regime) {
        case Regime::narrow_pulse: {
          CHECK(s.ray.segments.size() >= 1);
          CHECK(s.ray.segments.size() <= 6);
          for (const auto* group : {&s.transfer.density, &s.transfer.color})
            for (const PiecewiseLinear& f : *group)
              for (std::size_t k = 1; k < f.scalar.size(); ++k) {
                const double gap = f.scalar[k] - f.scalar[k - 1];
                if (gap <= 1e-12) narrow_seen = true;
                if (f.scalar[k] == std::nextafter(f.scalar[k - 1], 2.0)) ulp_wide_seen = true;
              }
          break;
        }
        case Regime::long_ray:
          CHECK(s.ray.segments.size() == 10000);
          break;
        case Regime::out_of_range: {
          const std::vector<double> bps = s.transfer.breakpoints();
          const double far = s.ray.segments.front().scalar_far;
          CHECK((far < bps.front() || far > bps.back()));
          break;
        }
        default: break;
      }
    }
    if (regime == Regime::narrow_pulse) {
      CHECK(narrow_seen);
      CHECK(ulp_wide_seen);
    }
  }
}

TEST_CASE("stress: a written worst sample replays to the same error", "[stress]") {
  const TempDir dir;
  StressOptions opt;
  opt.count = 300;
  opt.seed = 8;
  opt.regimes = {Regime::steep_down, Regime::narrow_pulse, Regime::out_of_range};
  opt.methods = {parse_method_spec("exact"), parse_method_spec("riemann:n=2")};
  StressReport report = run_stress(opt);
  write_worst_cases(report, (dir.path / "worst").string());
  int replayed = 0;
  for (const RegimeStress& rs : report.regimes)
    for (const MethodStress& m : rs.methods) {
      INFO("regime " << rs.regime << " method " << m.method);
      REQUIRE(m.worst.present);
      REQUIRE_FALSE(m.worst.file.empty());
      const Case c = read_case_file(m.worst.file);
      CHECK(c.name == m.worst.replay.name);
      CHECK(c.description.find("seed 8") != std::string::npos);
      const CaseEvaluation ev = evaluate_case(c, {parse_method_spec(m.method)}, [] {
        EvalOptions e;
        e.measure_time = false;
        return e;
      }());
      REQUIRE(ev.rays.size() == 1);
      const MethodOutcome& o = ev.rays[0].methods[0];
      const SampleScore s = score_sample(o.result, ev.rays[0].reference.intensity, !o.failure.empty());
      CHECK(s.rel == m.worst.rel_error);  // bit for bit: same doubles in, same code
      CHECK(s.rel == m.rel.max);
      for (int ch = 0; ch < kChannels; ++ch) CHECK(o.result.intensity[ch] == m.worst.value[ch]);
      ++replayed;
    }
  CHECK(replayed == 6);
}

TEST_CASE("stress: the command writes worst samples that `rayint eval` replays", "[stress][cli]") {
  const TempDir dir;
  const CliRun run = run_cli(dir.path,
                             "stress --count 40 --seed 4 --regime steep_up,out_of_range "
                             "--json -q -o report.json --worst-dir worst");
  REQUIRE(run.status == 0);
  CHECK(run.out.empty());
  CHECK(run.err.empty());
  const auto report = nlohmann::json::parse(slurp(dir.path / "report.json"));
  REQUIRE(report["regimes"].size() == 2);
  for (const auto& regime : report["regimes"]) {
    const auto& worst = regime["methods"][0]["worst"];
    const std::string file = worst["file"];
    INFO(file);
    const CliRun eval = run_cli(dir.path, "eval '" + file + "' --methods exact --no-timing");
    REQUIRE(eval.status == 0);
    const auto out = nlohmann::json::parse(eval.out);
    const auto& rel = out["cases"][0]["rays"][0]["methods"]["exact"]["rel_error"];
    double max_rel = 0;
    for (const auto& x : rel) max_rel = std::max(max_rel, x.get<double>());
    CHECK(max_rel == worst["rel_error"].get<double>());
  }

  // The same run again: the same bytes (progress, which goes to stderr, is off).
  REQUIRE(run_cli(dir.path, "stress --count 40 --seed 4 --regime steep_up,out_of_range --json -q "
                            "-o again.json --worst-dir worst")
              .status == 0);
  CHECK(slurp(dir.path / "again.json") == slurp(dir.path / "report.json"));

  // The table names every regime and the pooled row.
  const CliRun table = run_cli(dir.path, "stress --count 40 --seed 4 --regime steep_up -q --no-worst");
  REQUIRE(table.status == 0);
  CHECK(table.out.find("steep_up") != std::string::npos);
  CHECK(table.out.find("\nall ") != std::string::npos);
}

TEST_CASE("stress: bad options are one line on stderr and exit 2", "[stress][cli]") {
  const TempDir dir;
  for (const std::string& args :
       {std::string("stress --regime nosuch"), std::string("stress --methods nosuch"),
        std::string("stress --methods riemann:n=abc"), std::string("stress --count 0"),
        std::string("stress --count x"), std::string("stress --seed -1")}) {
    INFO(args);
    const CliRun r = run_cli(dir.path, args + " -q --no-worst");
    check_usage_error(r);
  }
  CHECK(run_cli(dir.path, "stress --regime nosuch -q").err.find("--regime") != std::string::npos);
  CHECK(run_cli(dir.path, "stress --methods nosuch -q").err.find("--methods") != std::string::npos);
  CHECK(fs::is_empty(dir.path));  // nothing written
}

TEST_CASE("stress: scoring -- underflow by absolute error, p99 by nearest rank, median of the middles",
          "[stress]") {
  const double inf = std::numeric_limits<double>::infinity();
  // Above the threshold: relative error and ulps.
  ValueScore s = score_value(1.0 + 2e-16, {1.0, 0.0});
  CHECK_FALSE(s.underflow);
  CHECK(s.rel == Approx(2.220446049250313e-16));
  CHECK(s.ulp == Approx(1.0));
  // Below it (and at exactly 0): the absolute error alone.
  s = score_value(3e-301, {1e-295, 0.0});
  CHECK(s.underflow);
  CHECK(s.rel == 0.0);
  CHECK(s.abs == Approx(1e-295));
  s = score_value(0.0, {0.0, 0.0});
  CHECK(s.underflow);
  CHECK(s.abs == 0.0);
  s = score_value(std::nan(""), {1.0, 0.0});
  CHECK_FALSE(s.finite);
  CHECK(s.abs == inf);

  RayResult r;
  r.intensity = {1.0, 5e-300, 2.0};
  r.transmittance = {0.5, 0.5, 0.5};
  SampleScore ss = score_sample(r, {ExtendedValue{1.0, 0.0}, {5e-300, 1e-316}, {2.0, 0.0}}, false);
  CHECK(ss.finite);
  CHECK(ss.scored);
  CHECK(ss.underflow);
  CHECK(ss.rel == 0.0);
  CHECK(ss.abs_underflow == Approx(1e-316));
  r.transmittance[1] = inf;  // a non-finite transmittance makes the sample non-finite
  CHECK_FALSE(score_sample(r, {ExtendedValue{1.0, 0.0}, {5e-300, 0.0}, {2.0, 0.0}}, false).finite);
  CHECK_FALSE(score_sample(RayResult{}, {}, /*failed=*/true).finite);

  std::vector<double> v;
  for (int i = 1; i <= 200; ++i) v.push_back(i);
  const ErrorStats st = error_stats(v);
  CHECK(st.max == 200);
  CHECK(st.p99 == 198);  // ceil(0.99 * 200) = 198th smallest
  CHECK(st.median == 100.5);  // 200 values: the mean of the 100th and 101st smallest
  CHECK(error_stats({}).max == 0.0);
  CHECK(error_stats({7.0}).p99 == 7.0);
}

TEST_CASE("stress: the opt-in tau regimes draw their optical depths and are not in the default run", "[stress]") {
  struct Range {
    Regime regime;
    const char* name;
    double lo, hi;
  };
  for (const Range& r : {Range{Regime::tau_moderate, "tau_moderate", 0.1, 10.0},
                         Range{Regime::tau_thin, "tau_thin", 1e-8, 1e-3},
                         Range{Regime::tau_thick, "tau_thick", 20.0, 1000.0}}) {
    INFO(r.name);
    Regime parsed{};
    REQUIRE(parse_regime(r.name, parsed));
    CHECK(parsed == r.regime);
    CHECK(std::find(stress_regimes().begin(), stress_regimes().end(), r.regime) == stress_regimes().end());
    CHECK(std::find(all_regimes().begin(), all_regimes().end(), r.regime) == all_regimes().end());
    std::mt19937_64 rng(11);
    for (int i = 0; i < 200; ++i) CHECK(in_range(optical_depth(sample_piece(r.regime, rng).piece), r.lo, r.hi));
  }
}

TEST_CASE("stress: negative outputs are counted, finite ones only", "[stress]") {
  // RK4 with one step on thick pieces: the step's amplification R > 1, so I = R B + (1 - R) kappa
  // goes negative whenever the background B is small against kappa (always when B = 0). The
  // count must match a recount of the same samples, and exact must have none.
  StressOptions o;
  o.count = 200;
  o.seed = 4;
  o.regimes = {Regime::tau_thick};
  o.methods = parse_method_list("exact,rk4:n=1");
  o.threads = 1;
  const StressReport r = run_stress(o);
  REQUIRE(r.regimes.size() == 1);
  REQUIRE(r.regimes[0].methods.size() == 2);
  long expected = 0;
  for (long i = 0; i < r.regimes[0].samples; ++i) {
    const RaySample sample = stress_sample(o.seed, Regime::tau_thick, i);
    const RayResult res = make_integrator(o.methods[1], sample.transfer)->integrate(sample.ray, nullptr);
    bool finite = true, negative = false;
    for (int c = 0; c < 3; ++c) {
      finite = finite && std::isfinite(res.intensity[c]) && std::isfinite(res.transmittance[c]);
      negative = negative || res.intensity[c] < 0.0 || res.transmittance[c] < 0.0;
    }
    if (finite && negative) ++expected;
  }
  CHECK(expected > 0);
  CHECK(r.regimes[0].methods[0].negative == 0);
  CHECK(r.regimes[0].methods[1].negative == expected);
  CHECK(r.overall[1].negative == expected);
}
