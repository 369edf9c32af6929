// Transfer functions with jumps (a scalar repeated: left value, then right value; issue 27):
// the model's values and one-sided limits, the splitter's pieces, the exact integrator against
// the 50-digit reference on rays crossing, starting on, ending on and sitting on a jump in every
// regime, the reference against itself without jumps (composition of the two sides), the jump as
// the limit of ever steeper ramps, and ParaView's shipped presets with repeated scalars and Step
// colour spaces imported as true jumps.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "rayint/generators/regimes.hpp"
#include "rayint/input/paraview_preset.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/model/ray_gradient.hpp"
#include "rayint/reference/reference.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using rayint::test::Tolerances;

namespace {

namespace fs = std::filesystem;

// Relative error within rel, or, where the reference itself underflows, absolutely tiny (as
// tests/test_exact.cpp's within()).
bool within(double x, const ExtendedValue& ref, double rel) {
  if (!std::isfinite(x)) return false;
  if (relative_error(x, ref) <= rel) return true;
  return std::fabs(ref.hi) < 1e-290 && absolute_error(x, ref) <= Tolerances::exact_abs_underflow;
}

// One function that is piece a's line on [0, x] and piece b's on [x, 1], jumping at x.
PiecewiseLinear jump_at(double x, double a_far, double a_exit, double b_far, double b_exit) {
  return {{0.0, x, x, 1.0}, {a_far, a_exit, b_far, b_exit}};
}

TransferFunctions jump_tf(double x, const ChannelPiece& a, const ChannelPiece& b) {
  return test::uniform_tf(jump_at(x, a.rho_far, a.rho_exit, b.rho_far, b.rho_exit),
                          jump_at(x, a.kappa_far, a.kappa_exit, b.kappa_far, b.kappa_exit));
}

}  // namespace

TEST_CASE("a jump: the value at it is the left one, limits from each side, at most two points",
          "[tfstep][tf]") {
  const PiecewiseLinear f{{0.0, 0.5, 0.5, 1.0}, {1.0, 2.0, 5.0, 3.0}};
  CHECK(f.has_jump());
  CHECK(f(0.5) == 2.0);
  CHECK(f.limit(0.5, false) == 2.0);
  CHECK(f.limit(0.5, true) == 5.0);
  CHECK(f(0.25) == 1.5);
  CHECK(f(0.75) == 4.0);
  CHECK(f.limit(0.75, true) == 4.0);
  CHECK(f(-1.0) == 1.0);
  CHECK(f(2.0) == 3.0);
  // Jumps at the end points: the end value holds beyond them.
  const PiecewiseLinear first{{0.0, 0.0, 1.0}, {1.0, 4.0, 2.0}};
  CHECK(first(-0.5) == 1.0);
  CHECK(first(0.0) == 1.0);
  CHECK(first.limit(0.0, true) == 4.0);
  CHECK(first(0.5) == 3.0);
  const PiecewiseLinear last{{0.0, 1.0, 1.0}, {1.0, 2.0, 7.0}};
  CHECK(last(1.0) == 2.0);
  CHECK(last.limit(1.0, true) == 7.0);
  CHECK(last(1.5) == 7.0);
  CHECK(std::isnan(f.limit(std::nan(""), true)));
  // Without a jump limit() is operator(), bit for bit, on both sides.
  const PiecewiseLinear g{{0.0, 0.3, 1.0}, {0.7, 0.1, 2.0}};
  CHECK_FALSE(g.has_jump());
  for (const double s : {-1.0, 0.0, 0.1, 0.3, 0.31, 0.99, 1.0, 3.0}) {
    CHECK(g.limit(s, true) == g(s));
    CHECK(g.limit(s, false) == g(s));
  }
  CHECK(check_points(f).empty());
  CHECK(check_points(PiecewiseLinear{{0.0, 0.5, 0.5, 0.5}, {1.0, 2.0, 3.0, 4.0}}).find("at most twice") !=
        std::string::npos);
  CHECK(check_points(PiecewiseLinear{{0.0, 0.5, 0.4}, {1.0, 2.0, 3.0}}).find("non-decreasing") !=
        std::string::npos);
  TransferFunctions tf = test::uniform_tf(f, test::constant(1.0));
  CHECK(tf.has_jump());
}

TEST_CASE("the splitter's pieces at a jump take the limit from inside each piece, as append_pieces",
          "[tfstep][splitter]") {
  // Density jumps at 0.4 and 0.7 (the second only in channel g), colour at 0.4 and at its first point.
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{0.0, 0.4, 0.4, 1.0}, {1.0, 2.0, 6.0, 3.0}},
                PiecewiseLinear{{0.0, 0.4, 0.4, 0.7, 0.7, 1.0}, {1.0, 2.0, 6.0, 5.0, 0.5, 3.0}},
                PiecewiseLinear{{0.0, 1.0}, {1.0, 3.0}}};
  tf.color = {PiecewiseLinear{{0.2, 0.2, 0.4, 0.4, 0.9}, {0.0, 1.0, 2.0, 0.5, 1.5}},
              PiecewiseLinear{{0.0, 1.0}, {0.3, 0.6}}, PiecewiseLinear{{0.4, 0.4}, {0.1, 0.9}}};
  for (const auto& f : tf.density) REQUIRE(check_points(f).empty());
  for (const auto& f : tf.color) REQUIRE(check_points(f).empty());
  const PieceSplitter splitter(tf);
  const std::vector<double> bps = tf.breakpoints();
  const std::vector<double> scalars = {-0.1, 0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 0.8, 1.0, 1.2};
  int on_jump_ends = 0;
  for (const double a : scalars)
    for (const double b : scalars) {
      const Segment seg{1.5, a, b};
      std::vector<Piece> plain;
      append_pieces(tf, seg, bps, plain);
      const std::vector<Piece>& fast = splitter.pieces(seg);
      INFO("segment " << a << " -> " << b);
      REQUIRE(fast.size() == plain.size());
      for (std::size_t k = 0; k < plain.size(); ++k) {
        const Piece& p = plain[k];
        for (int c = 0; c < kChannels; ++c) {
          CHECK(fast[k].rho_far[c] == p.rho_far[c]);
          CHECK(fast[k].rho_exit[c] == p.rho_exit[c]);
          CHECK(fast[k].kappa_far[c] == p.kappa_far[c]);
          CHECK(fast[k].kappa_exit[c] == p.kappa_exit[c]);
          // Independently of both: each end is the limit from inside the piece, i.e. the value
          // a little way into it.
          if (p.scalar_far != p.scalar_exit) {
            const double into_far = p.scalar_far + 1e-9 * (p.scalar_exit - p.scalar_far);
            const double into_exit = p.scalar_exit + 1e-9 * (p.scalar_far - p.scalar_exit);
            CHECK(std::fabs(p.rho_far[c] - tf.density[c](into_far)) < 1e-7);
            CHECK(std::fabs(p.rho_exit[c] - tf.density[c](into_exit)) < 1e-7);
            CHECK(std::fabs(p.kappa_far[c] - tf.color[c](into_far)) < 1e-7);
            CHECK(std::fabs(p.kappa_exit[c] - tf.color[c](into_exit)) < 1e-7);
            if (tf.density[c].limit(p.scalar_far, true) != tf.density[c].limit(p.scalar_far, false)) ++on_jump_ends;
          } else {
            CHECK(p.rho_far[c] == tf.density[c](p.scalar_far));
          }
        }
        CHECK(fast[k].length == p.length);
      }
    }
  CHECK(on_jump_ends > 20);  // the loop did visit piece ends on jumps
}

TEST_CASE("exact with jumps against the 50-digit reference, regime by regime",
          "[tfstep][exact][regimes]") {
  // Per regime, 40 pairs of pieces a, b drawn from it; the transfer function is a's line on
  // [0, x] and b's on [x, 1], x = L_a / (L_a + L_b), so a segment of length L_a + L_b from 0 to 1
  // integrates a then b across the jump. Seven rays per pair: across the jump both ways, starting
  // on it both ways, ending on it both ways, and a constant scalar exactly on it.
  std::mt19937_64 rng(2027);
  const std::vector<std::string> methods = {"exact", "exact:path=batch"};
  double worst = 0.0;
  long rays = 0;
  for (const Regime regime : all_regimes()) {
    double worst_regime = 0.0;
    for (int i = 0; i < 40; ++i) {
      const RegimeSample sa = sample_piece(regime, rng), sb = sample_piece(regime, rng);
      const double la = sa.piece.length, lb = sb.piece.length, x = la / (la + lb);
      if (!(x > 0.0 && x < 1.0 && std::isfinite(la + lb))) continue;
      const TransferFunctions tf = jump_tf(x, sa.piece, sb.piece);
      const Rgb bg{sa.incoming, sa.incoming, sa.incoming};
      const double l = la + lb;
      const std::vector<Ray> cases = {
          Ray{bg, {{l, 0.0, 1.0}}}, Ray{bg, {{l, 1.0, 0.0}}}, Ray{bg, {{lb, x, 1.0}}},
          Ray{bg, {{la, x, 0.0}}},  Ray{bg, {{la, 0.0, x}}},  Ray{bg, {{lb, 1.0, x}}},
          Ray{bg, {{la, x, x}}}};
      for (const std::string& spec : methods) {
        const auto m = make_integrator(parse_method_spec(spec), tf);
        for (std::size_t r = 0; r < cases.size(); ++r) {
          const ReferenceRay ref = reference_ray(tf, cases[r]);
          const RayResult got = m->integrate(cases[r], nullptr);
          INFO("regime " << regime_name(regime) << " " << spec << " ray " << r << " x " << x << " a: L "
                         << la << " rho " << sa.piece.rho_far << "," << sa.piece.rho_exit << " kappa "
                         << sa.piece.kappa_far << "," << sa.piece.kappa_exit << " b: L " << lb << " rho "
                         << sb.piece.rho_far << "," << sb.piece.rho_exit << " kappa " << sb.piece.kappa_far
                         << "," << sb.piece.kappa_exit << " got " << got.intensity[0] << " ref "
                         << ref.intensity[0].hi);
          CHECK(within(got.intensity[0], ref.intensity[0], Tolerances::exact_rel));
          CHECK(within(got.transmittance[0], ref.transmittance[0], Tolerances::exact_rel));
          if (std::fabs(ref.intensity[0].hi) > 1e-290)
            worst_regime = std::max(worst_regime, relative_error(got.intensity[0], ref.intensity[0]));
          ++rays;
        }
      }
    }
    WARN("[tfstep] jumps, regime " << regime_name(regime) << ": exact vs 50-digit reference, worst rel "
                                   << worst_regime);
    worst = std::max(worst, worst_regime);
  }
  WARN("[tfstep] jumps: " << rays << " rays, worst relative error of the intensity " << worst);
  CHECK(rays > 12 * 40 * 7 * 2 * 9 / 10);

  // The ray-level regimes (narrow pulses 1e-15 wide, 10^4-segment rays, out-of-range scalars):
  // their transfer functions with every interior breakpoint made a jump (right value: the value
  // there times 3, plus 0.5).
  int with_jumps = 0;
  for (const Regime regime : ray_regimes()) {
    for (int i = 0; i < 6; ++i) {
      RaySample s = sample_ray(regime, rng);
      for (auto* group : {&s.transfer.density, &s.transfer.color})
        for (PiecewiseLinear& f : *group) {
          PiecewiseLinear j;
          for (std::size_t k = 0; k < f.scalar.size(); ++k) {
            j.scalar.push_back(f.scalar[k]);
            j.value.push_back(f.value[k]);
            if (k > 0 && k + 1 < f.scalar.size()) {
              j.scalar.push_back(f.scalar[k]);
              j.value.push_back(3.0 * f.value[k] + 0.5);
            }
          }
          f = j;
        }
      if (!s.transfer.has_jump()) continue;  // no interior breakpoint to make a jump of
      ++with_jumps;
      const ReferenceRay ref = reference_ray(s.transfer, s.ray);
      const auto m = make_integrator(parse_method_spec("exact"), s.transfer);
      const RayResult got = m->integrate(s.ray, nullptr);
      for (int c = 0; c < kChannels; ++c) {
        INFO("regime " << regime_name(regime) << " sample " << i << " channel " << c);
        CHECK(within(got.intensity[c], ref.intensity[c], Tolerances::exact_rel));
        CHECK(within(got.transmittance[c], ref.transmittance[c], Tolerances::exact_rel));
      }
    }
  }
  CHECK(with_jumps >= 9);
}

TEST_CASE("the reference across a jump is the composition of the two sides without a jump",
          "[tfstep][reference]") {
  // Independent of the jump handling: the jump ray [0 -> 1] of length 2L equals the ray [0 -> 1/2]
  // of length L through a's function alone, then [1/2 -> 1] through b's alone (both continuous),
  // its intensity the second's background. Lengths halve exactly; the only extra rounding is the
  // intermediate intensity's (one double), so the two agree to a few ulps.
  std::mt19937_64 rng(99);
  double worst = 0.0;
  for (const Regime regime : all_regimes()) {
    for (int i = 0; i < 20; ++i) {
      const RegimeSample sa = sample_piece(regime, rng), sb = sample_piece(regime, rng);
      ChannelPiece a = sa.piece, b = sb.piece;
      b.length = a.length;
      const TransferFunctions jump = jump_tf(0.5, a, b);
      const TransferFunctions left = test::uniform_tf(test::line(0.0, a.rho_far, 0.5, a.rho_exit),
                                                      test::line(0.0, a.kappa_far, 0.5, a.kappa_exit));
      const TransferFunctions right = test::uniform_tf(test::line(0.5, b.rho_far, 1.0, b.rho_exit),
                                                       test::line(0.5, b.kappa_far, 1.0, b.kappa_exit));
      const Rgb bg{sa.incoming, sa.incoming, sa.incoming};
      for (const bool up : {true, false}) {
        const ReferenceRay whole = reference_ray(jump, Ray{bg, {{2.0 * a.length, up ? 0.0 : 1.0, up ? 1.0 : 0.0}}});
        const TransferFunctions& first = up ? left : right;
        const TransferFunctions& second = up ? right : left;
        const ReferenceRay r1 = reference_ray(first, Ray{bg, {{a.length, up ? 0.0 : 1.0, 0.5}}});
        const Rgb mid{r1.intensity[0].hi, r1.intensity[0].hi, r1.intensity[0].hi};
        const ReferenceRay r2 = reference_ray(second, Ray{mid, {{a.length, 0.5, up ? 1.0 : 0.0}}});
        INFO("regime " << regime_name(regime) << " up " << up << " whole " << whole.intensity[0].hi
                       << " composed " << r2.intensity[0].hi);
        CHECK(within(r2.intensity[0].hi, whole.intensity[0], 1e-14));
        const double t = r1.transmittance[0].hi * r2.transmittance[0].hi;
        CHECK(within(t, whole.transmittance[0], 1e-14));
        if (std::fabs(whole.intensity[0].hi) > 1e-290)
          worst = std::max(worst, relative_error(r2.intensity[0].hi, whole.intensity[0]));
      }
    }
  }
  WARN("[tfstep] reference with a jump vs composed without: worst rel " << worst);
}

TEST_CASE("a jump is the limit of ever steeper ramps", "[tfstep][exact]") {
  // rho: 1 -> 2 on [0, 0.5], jumping to 6 -> 3 on [0.5, 1]; kappa 0.2 -> 0.4, jumping to 1.5 -> 0.9.
  // The ramp of width w replaces the jump by a line from (0.5, left) to (0.5 + w, right line's
  // value there). Over the ramp's length L w the integrand differs by O(1): |I(w) - I(0)| ~ C w.
  const PiecewiseLinear rho_jump{{0.0, 0.5, 0.5, 1.0}, {1.0, 2.0, 6.0, 3.0}};
  const PiecewiseLinear kappa_jump{{0.0, 0.5, 0.5, 1.0}, {0.2, 0.4, 1.5, 0.9}};
  const TransferFunctions jump = test::uniform_tf(rho_jump, kappa_jump);
  const auto ramp = [](const PiecewiseLinear& f, double w) {
    const double s = 0.5 + w;
    return PiecewiseLinear{{0.0, 0.5, s, 1.0}, {f.value[0], f.value[1], f.value[2] + (f.value[3] - f.value[2]) * (w / 0.5), f.value[3]}};
  };
  for (const bool up : {true, false}) {
    const Ray ray{{0.3, 0.3, 0.3}, {{1.7, up ? 0.0 : 1.0, up ? 1.0 : 0.0}}};
    const ReferenceRay ref_jump = reference_ray(jump, ray);
    const auto exact = make_integrator(parse_method_spec("exact"), jump);
    const RayResult at_jump = exact->integrate(ray, nullptr);
    CHECK(within(at_jump.intensity[0], ref_jump.intensity[0], Tolerances::exact_rel));
    double previous = 0.0;
    for (int d = 1; d <= 12; ++d) {
      const double w = std::pow(10.0, -d);
      const TransferFunctions tf = test::uniform_tf(ramp(rho_jump, w), ramp(kappa_jump, w));
      const auto m = make_integrator(parse_method_spec("exact"), tf);
      const double e_exact = relative_error(m->integrate(ray, nullptr).intensity[0], ref_jump.intensity[0]);
      const ReferenceRay ref_ramp = reference_ray(tf, ray);
      // The reference's own limit: its ramp against its jump, in 50 digits (no rounding floor).
      const double e_ref = relative_error(ref_ramp.intensity[0].hi, ref_jump.intensity[0]);
      INFO("up " << up << " width " << w << " exact(ramp) vs reference(jump) " << e_exact
                 << " reference(ramp) vs reference(jump) " << e_ref);
      // First order: each tenfold narrower ramp is 5 to 20 times closer (measured ~10), until the
      // difference meets double rounding of the exact result (~1e-16).
      if (d > 1 && previous > 1e-13) {
        CHECK(e_ref < previous / 5);
        CHECK(e_ref > previous / 20);
      }
      CHECK(e_ref < 2.0 * w);  // measured C ~ 0.3
      if (d == 12) CHECK(e_exact < 1e-11);
      previous = e_ref;
      if (d == 1 || d == 6 || d == 12)
        WARN("[tfstep] ramp width " << w << (up ? " (up)" : " (down)") << ": reference(ramp) vs reference(jump) "
                                    << e_ref << ", exact(ramp) " << e_exact);
    }
  }
}

TEST_CASE("ParaView's presets with repeated scalars and Step colour spaces import as true jumps",
          "[tfstep][paraview][tf]") {
  // ParaView 5.11's built-in list as its pvpython exported it (tests/data/tf/, written by
  // scripts/paraview-presets.py): the 3 presets with a repeated RGBPoints scalar and the 10 Step
  // presets. Each repeated scalar must be a jump of rayint's colour (the left value what VTK's
  // lookup gives at it: the first node's colour; just above it the second's), and every Step
  // interval a jump; the exact integral across the whole range matches the 50-digit reference.
  const fs::path file = fs::path(RAYINT_SOURCE_DIR) / "tests" / "data" / "tf" / "paraview-5.11-presets.json";
  struct Expect {
    const char* name;
    bool step;
    int repeated;
  };
  int presets = 0;
  for (const Expect& e : {Expect{"Cool to Warm (Extended)", false, 1}, Expect{"Yellow - Gray - Blue", false, 1},
                          Expect{"Muted Blue-Green", false, 3}, Expect{"KAAMS Step", true, 0},
                          Expect{"Spectrum Step", true, 0}, Expect{"Warm Step", true, 0},
                          Expect{"Cool Step", true, 0}, Expect{"Blues Step", true, 0},
                          Expect{"Wild Flower Step", true, 0}, Expect{"Citrus Step", true, 0},
                          Expect{"Traffic Lights Step", true, 0},
                          Expect{"Traffic Lights For Deuteranopes Step", true, 0},
                          Expect{"Traffic Lights For Deuteranopes 2 Step", true, 0}}) {
    INFO(e.name);
    PresetImportRequest r;
    r.file = file.string();
    r.name = e.name;
    r.request_source = "test";
    const PresetImport imp = import_paraview_preset(r);
    ++presets;
    const TransferFunctions& tf = imp.result.transfer;
    for (const auto& f : tf.color) REQUIRE(check_points(f).empty());
    const auto& nodes = imp.preset.color.nodes;
    // Jumps in the colour (any channel): a scalar stored twice.
    std::vector<double> jumps;
    for (std::size_t k = 1; k < tf.color[0].scalar.size(); ++k)
      if (tf.color[0].scalar[k] == tf.color[0].scalar[k - 1]) jumps.push_back(tf.color[0].scalar[k]);
    // Groups of repeated scalars: VTK's value at x is the first copy's colour, just above it the
    // curve of the interval the last copy starts. A jump wherever the two differ (Yellow - Gray -
    // Blue repeats a node with its own colour, Muted Blue-Green returns to the first colour after
    // four copies: no jump there, as in VTK).
    int repeated_seen = 0;
    for (std::size_t first = 0; first + 1 < nodes.size();) {
      std::size_t last = first;
      while (last + 1 < nodes.size() && nodes[last + 1].x == nodes[first].x) ++last;
      if (last == first) {
        ++first;
        continue;
      }
      repeated_seen += static_cast<int>(last - first);
      const double x = nodes[first].x;
      bool differs = false;
      for (std::size_t c = 0; c < 3; ++c) {
        CHECK(tf.color[c](x) == imp.preset.color(x)[c]);  // VTK's value at x: the left one
        if (last + 1 < nodes.size()) {
          CHECK(tf.color[c].limit(x, true) == imp.preset.color.interval_value(last, x)[c]);
          CHECK(std::fabs(tf.color[c].limit(x, true) - nodes[last].rgb[c]) < 1e-3);  // up to the Lab round trip
        }
        differs = differs || nodes[last].rgb[c] != nodes[first].rgb[c];
      }
      if (differs) CHECK(std::find(jumps.begin(), jumps.end(), x) != jumps.end());
      first = last + 1;
    }
    CHECK(repeated_seen == e.repeated);
    if (e.step) {
      // Step: the right node's colour on (x_k, x_k+1], so a jump at x_k wherever the colours of
      // nodes k and k+1 differ (Traffic Lights Step repeats its first colour: no jump there).
      for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
        if (nodes[k].rgb != nodes[k + 1].rgb) {
          INFO("Step interval " << k);
          const auto at = std::find_if(jumps.begin(), jumps.end(), [&](double j) {
            return j >= nodes[k].x && j < nodes[k + 1].x;
          });
          CHECK(at != jumps.end());
        }
    }
    // No ramp one double wide is left: no two consecutive scalars one ulp apart.
    for (std::size_t k = 1; k < tf.color[0].scalar.size(); ++k)
      CHECK(std::nextafter(tf.color[0].scalar[k - 1], HUGE_VAL) != tf.color[0].scalar[k]);
    // A ray across the range both ways, and one starting on each jump.
    const double lo = nodes.front().x, hi = nodes.back().x;
    std::vector<Ray> rays = {Ray{{0.1, 0.2, 0.3}, {{2.0, lo - 0.1, hi + 0.1}}},
                             Ray{{0.1, 0.2, 0.3}, {{2.0, hi + 0.1, lo - 0.1}}}};
    for (const double x : jumps) rays.push_back(Ray{{0.0, 0.0, 0.0}, {{0.5, x, hi}, {0.5, x, lo}}});
    const auto m = make_integrator(parse_method_spec("exact"), tf);
    for (const Ray& ray : rays) {
      const ReferenceRay ref = reference_ray(tf, ray);
      const RayResult got = m->integrate(ray, nullptr);
      for (int c = 0; c < kChannels; ++c) CHECK(within(got.intensity[c], ref.intensity[c], Tolerances::exact_rel));
    }
  }
  CHECK(presets == 13);
}
