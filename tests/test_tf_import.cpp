// Transfer functions as renderers store them (issue 14): ParaView presets read into VTK's curves,
// checked against VTK 9.1 itself (tests/data/tf/vtk-eval.json, written by scripts/tf-fixtures.py
// with python3-vtk9), imported as rayint transfer functions under each opacity convention, and
// integrated with `exact`.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <initializer_list>
#include <string>
#include <tuple>
#include <vector>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/paraview_preset.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/model/tf_import.hpp"

namespace {

namespace fs = std::filesystem;
using rayint::OpacityConvention;
using rayint::PiecewiseLinear;
using rayint::TransferFunctions;

const fs::path kData = fs::path(RAYINT_SOURCE_DIR) / "tests" / "data" / "tf";

const nlohmann::json& vtk_eval() {
  static const nlohmann::json j = [] {
    std::ifstream in(kData / "vtk-eval.json");
    return nlohmann::json::parse(in);
  }();
  return j;
}

std::string preset_file_for(const std::string& name) {
  return (kData / (name.rfind("rayint ", 0) == 0 ? "exported-opacity.json" : "paraview-colormaps.json")).string();
}

rayint::PresetImport import(const std::string& name, OpacityConvention c, double distance, double tolerance) {
  rayint::PresetImportRequest r;
  r.file = preset_file_for(name);
  r.name = name;
  r.options.convention = c;
  r.options.distance = distance;
  r.options.tolerance = tolerance;
  r.request_source = "test";
  if (name.rfind("rayint ", 0) != 0) r.constant_opacity = 0.5;
  return rayint::import_paraview_preset(r);
}

double rel_diff(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale == 0.0 ? 0.0 : std::fabs(a - b) / scale;
}

// Random rays over [lo, hi] (scalars a little beyond, where the functions are constant), each
// 1-4 segments of length 0.05-2.
std::vector<rayint::Ray> random_rays(double lo, double hi, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  const double pad = 0.1 * (hi - lo);
  std::uniform_real_distribution<double> scalar(lo - pad, hi + pad), length(0.05, 2.0), bg(0.0, 1.0);
  std::uniform_int_distribution<int> segments(1, 4);
  std::vector<rayint::Ray> rays(static_cast<std::size_t>(count));
  for (rayint::Ray& r : rays) {
    r.background = {bg(rng), bg(rng), bg(rng)};
    double s = scalar(rng);
    for (int k = segments(rng); k > 0; --k) {
      const double next = scalar(rng);
      r.segments.push_back({length(rng), s, next});
      s = next;
    }
  }
  return rays;
}

// Largest relative (or absolute) difference of the exact intensities of two transfer functions over `rays`.
double max_image_difference(const TransferFunctions& a, const TransferFunctions& b,
                            const std::vector<rayint::Ray>& rays, bool absolute = false) {
  const rayint::ExactIntegrator ia(a), ib(b);
  double worst = 0.0;
  for (const rayint::Ray& r : rays) {
    const rayint::RayResult ra = ia.integrate(r, nullptr), rb = ib.integrate(r, nullptr);
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, absolute ? std::fabs(ra.intensity[c] - rb.intensity[c])
                                       : rel_diff(ra.intensity[c], rb.intensity[c]));
  }
  return worst;
}

TransferFunctions shared(const PiecewiseLinear& rho, const std::array<PiecewiseLinear, 3>& kappa) {
  TransferFunctions tf;
  tf.density = {rho, rho, rho};
  tf.color = kappa;
  return tf;
}

std::string preset_text(const std::string& name, const std::vector<double>& rgb, const std::vector<double>& pts) {
  nlohmann::json p{{"Name", name}, {"ColorSpace", "RGB"}, {"RGBPoints", rgb}, {"Points", pts}};
  return nlohmann::json::array({p}).dump();
}

}  // namespace

TEST_CASE("VTK curves as rayint evaluates them agree with VTK 9.1 on every preset fixture", "[tf]") {
  // The fixtures cover RGB, HSV (HSVWrap off, ParaView's default), Lab, Diverging, opacity
  // midpoints, sharpness 0.3-0.7 and a step (sharpness 1). Measured max difference: printed.
  for (const auto& p : vtk_eval()["presets"]) {
    const std::string name = p["name"].get<std::string>();
    INFO(name);
    const rayint::ParaViewPreset preset = rayint::read_paraview_preset_file(preset_file_for(name), name);
    double worst_rgb = 0.0, worst_opacity = 0.0;
    for (std::size_t i = 0; i < p["x"].size(); ++i) {
      const double x = p["x"][i].get<double>();
      const rayint::Rgb c = preset.color(x);
      for (int j = 0; j < 3; ++j) worst_rgb = std::max(worst_rgb, std::fabs(c[j] - p["rgb"][i][j].get<double>()));
      if (!p["opacity"].is_null())
        worst_opacity = std::max(worst_opacity, std::fabs((*preset.opacity)(x) - p["opacity"][i].get<double>()));
    }
    CHECK(worst_rgb <= 1e-12);
    CHECK(worst_opacity <= 1e-12);
    WARN("VTK 9.1 vs rayint's curves, " << name << ": max |rgb diff| " << worst_rgb << ", max |opacity diff| "
                                        << worst_opacity);
  }
}

TEST_CASE("linearised presets stay within the tolerance of VTK's own curves", "[tf]") {
  // Independent check of the adaptive linearisation: the imported piecewise-linear colour and
  // density against VTK 9.1's values at 401 equally spaced scalars plus every node. The import
  // claims max deviation <= tolerance at its probes; VTK's dense values must agree with that.
  for (const double tolerance : {1e-3, 1e-6}) {
    for (const auto& p : vtk_eval()["presets"]) {
      const std::string name = p["name"].get<std::string>();
      INFO(name << " tolerance " << tolerance);
      const rayint::PresetImport imp = import(name, OpacityConvention::density, 1.0, tolerance);
      const TransferFunctions& tf = imp.result.transfer;
      double worst_rgb = 0.0, worst_rho = 0.0;
      for (std::size_t i = 0; i < p["x"].size(); ++i) {
        const double x = p["x"][i].get<double>();
        for (int j = 0; j < 3; ++j)
          worst_rgb = std::max(worst_rgb, std::fabs(tf.color[j](x) - p["rgb"][i][j].get<double>()));
        if (!p["opacity"].is_null())
          worst_rho = std::max(worst_rho, std::fabs(tf.density[0](x) - p["opacity"][i].get<double>()));
      }
      CHECK(imp.result.color.converged);
      CHECK(imp.result.color.max_deviation <= tolerance);
      CHECK(worst_rgb <= tolerance);
      if (!p["opacity"].is_null()) CHECK(worst_rho <= imp.result.density.tolerance);
      WARN("import " << name << " tolerance " << tolerance << ": colour " << imp.result.color.nodes << " nodes ("
                     << imp.result.color.adaptive_intervals << " intervals linearised), reported max deviation "
                     << imp.result.color.max_deviation << ", against VTK " << worst_rgb << "; density "
                     << imp.result.density.nodes << " nodes, reported " << imp.result.density.max_deviation
                     << ", against VTK " << worst_rho);
      // RGB with sharpness 0 is exact: node for node, so VTK's values to rounding.
      if (imp.preset.color_space == "RGB") {
        CHECK(imp.result.color.exact());
        CHECK(worst_rgb <= 1e-15);
      }
    }
  }
}

TEST_CASE("must show: a preset with midpoints, imported, integrates exactly as the function written by hand", "[tf]") {
  // exported-opacity.json, "rayint midpoints (sharpness 0)": RGBPoints (0: .9 .1 .2), (.5: .2 .8 .3),
  // (1: .1 .3 .9); opacity Points (x, y, midpoint, sharpness) = (0, 0, .25, 0), (.5, .4, .75, 0),
  // (.75, .8, .5, 0), (1, .1, .5, 0). By hand, vtkPiecewiseFunction's midpoint m puts the value
  // (y1 + y2)/2 at x1 + m(x2 - x1), linear on both sides: a node at 0 + .25 * .5 = .125 with
  // value .2, and one at .5 + .75 * .25 = .6875 with value .6; m = .5 adds no bend.
  const PiecewiseLinear rho_by_hand{{0.0, 0.125, 0.5, 0.6875, 0.75, 1.0}, {0.0, 0.2, 0.4, 0.6, 0.8, 0.1}};
  const std::array<PiecewiseLinear, 3> kappa_by_hand{PiecewiseLinear{{0.0, 0.5, 1.0}, {0.9, 0.2, 0.1}},
                                                     PiecewiseLinear{{0.0, 0.5, 1.0}, {0.1, 0.8, 0.3}},
                                                     PiecewiseLinear{{0.0, 0.5, 1.0}, {0.2, 0.3, 0.9}}};
  const std::vector<rayint::Ray> rays = random_rays(0.0, 1.0, 2000, 14);
  struct Statement {
    OpacityConvention convention;
    double distance;
    double rho_scale;  // rho = opacity * rho_scale under this convention
  };
  for (const Statement st : {Statement{OpacityConvention::density, 1.0, 1.0},
                             Statement{OpacityConvention::nerf_sigma, 1.0, 1.0},
                             Statement{OpacityConvention::unit_distance, 0.25, 4.0}}) {
    INFO(rayint::convention_name(st.convention));
    const rayint::PresetImport imp = import("rayint midpoints (sharpness 0)", st.convention, st.distance, 1e-6);
    CHECK(imp.result.density.exact());
    CHECK(imp.result.color.exact());
    PiecewiseLinear rho = rho_by_hand;
    for (double& v : rho.value) v *= st.rho_scale;
    const double diff = max_image_difference(imp.result.transfer, shared(rho, kappa_by_hand), rays);
    CHECK(diff <= 1e-13);
    WARN("midpoint preset vs by hand (" << rayint::convention_name(st.convention)
                                        << "), 2000 rays: max rel diff " << diff);
  }
}

TEST_CASE("one visual transfer function stated in each opacity convention gives the same exact image", "[tf]") {
  // The visual function: density rho and straight colour kappa. Two forms of it:
  //  (a) piecewise linear rho: stated as density, NeRF sigma (both: opacity = rho) and opacity per
  //      unit distance D (opacity = rho D) it is representable exactly;
  //  (b) piecewise-constant rho with steps (sharpness 1): also as opacity per sample at spacing d,
  //      alpha = 1 - e^{-rho d} (constant alpha gives constant -ln(1 - alpha)/d), so all four
  //      conventions state it exactly.
  //  (c) (a) as opacity per sample: the renderer interpolates alpha linearly between its nodes, so
  //      the stated function is alpha-linear; stated densely (nodes every 1/256) the import's
  //      linearised -ln(1 - alpha)/d must agree with (a) to the bound of the two approximations.
  const std::vector<double> rgb{0.0, 0.9, 0.1, 0.2, 0.5, 0.2, 0.8, 0.3, 1.0, 0.1, 0.3, 0.9};
  const std::vector<double> xs{0.0, 0.3, 0.6, 1.0};
  const std::vector<double> rho{0.5, 3.0, 1.5, 0.2};
  const double D = 2.5, d = 0.1;
  const std::vector<rayint::Ray> rays = random_rays(0.0, 1.0, 2000, 15);
  rayint::test::TempDir dir;
  auto imported = [&](const std::vector<double>& pts, OpacityConvention c, double dist, double tol = 1e-9) {
    dir.write("p.json", preset_text("p", rgb, pts));
    rayint::PresetImportRequest r;
    r.file = (dir.path / "p.json").string();
    r.options = {c, dist, tol};
    r.request_source = "test";
    return rayint::import_paraview_preset(r).result;
  };
  auto points = [&](auto opacity_of, double sharpness) {
    std::vector<double> pts;
    for (std::size_t k = 0; k < xs.size(); ++k) pts.insert(pts.end(), {xs[k], opacity_of(rho[k]), 0.5, sharpness});
    return pts;
  };
  const auto ident = [](double r) { return r; };
  const auto per_unit = [&](double r) { return r * D; };
  const auto per_sample = [&](double r) { return -std::expm1(-r * d); };

  // Each import (points, convention, distance) states `density` exactly: the import says so and
  // its images agree with those of `density` to 1e-13.
  using Import = std::tuple<std::vector<double>, OpacityConvention, double>;
  const auto check_exact = [&](const char* what, const TransferFunctions& density, std::initializer_list<Import> imports) {
    for (const auto& [pts, c, dist] : imports) {
      const rayint::TfImport t = imported(pts, c, dist);
      CHECK(t.density.exact());
      const double diff = max_image_difference(density, t.transfer, rays);
      CHECK(diff <= 1e-13);
      WARN(what << ", " << rayint::convention_name(c) << " vs density: max rel diff " << diff);
    }
  };
  // (a)
  const TransferFunctions a_density = imported(points(ident, 0.0), OpacityConvention::density, 1.0).transfer;
  check_exact("(a) linear rho", a_density,
              {Import{points(ident, 0.0), OpacityConvention::nerf_sigma, 1.0},
               Import{points(per_unit, 0.0), OpacityConvention::unit_distance, D}});
  // (b)
  const TransferFunctions b_density = imported(points(ident, 1.0), OpacityConvention::density, 1.0).transfer;
  check_exact("(b) stepped rho", b_density,
              {Import{points(ident, 1.0), OpacityConvention::nerf_sigma, 1.0},
               Import{points(per_unit, 1.0), OpacityConvention::unit_distance, D},
               Import{points(per_sample, 1.0), OpacityConvention::sample_distance, d}});
  // (c) alpha nodes every 1/256 of each interval, from the linear rho of (a).
  std::vector<double> dense;
  const PiecewiseLinear rho_a{xs, rho};
  for (std::size_t k = 0; k + 1 < xs.size(); ++k)
    for (int i = 0; i < 256; ++i) {
      const double x = xs[k] + (xs[k + 1] - xs[k]) * i / 256.0;
      dense.insert(dense.end(), {x, per_sample(rho_a(x)), 0.5, 0.0});
    }
  dense.insert(dense.end(), {xs.back(), per_sample(rho.back()), 0.5, 0.0});
  const rayint::TfImport c_import = imported(dense, OpacityConvention::sample_distance, d, 1e-7);
  // Bound, derived: on an interval of width h with rho linear, alpha = 1 - e^{-rho d} has
  // |alpha''| = (d rho')^2 e^{-rho d} <= (d rho')^2, so linear interpolation of alpha errs by at most
  // h^2/8 (d rho')^2 = (0.3/256)^2/8 * (0.1 * 2.5/0.3)^2 = 1.2e-7 (the steepest interval); in rho,
  // divide by (1 - alpha) d >= e^{-0.3} * 0.1: 1.6e-6, plus the import's 1e-7 * max rho = 3e-7.
  // A density error |delta| <= eps changes the intensity by at most eps * L * (max kappa + max
  // emission + max background) <= 1.9e-6 * 8 * (0.9 + 0.9 + 1) = 4.3e-5 (L <= 4 segments of <= 2).
  const double diff = max_image_difference(a_density, c_import.transfer, rays, /*absolute=*/true);
  CHECK(diff <= 4.3e-5);
  WARN("(c) linear rho stated per sample (alpha-linear, dense nodes) vs density: max abs diff " << diff
       << ", import max deviation " << c_import.density.max_deviation << " over " << c_import.density.nodes << " nodes");
}

TEST_CASE("density_from_opacity follows each convention's formula", "[tf]") {
  // Worked examples of docs/transfer-function-conventions.md.
  CHECK(rayint::density_from_opacity(0.4, OpacityConvention::density, 7.0) == 0.4);
  CHECK(rayint::density_from_opacity(0.4, OpacityConvention::nerf_sigma, 7.0) == 0.4);
  CHECK(rayint::density_from_opacity(0.4, OpacityConvention::unit_distance, 2.0) == 0.2);
  // alpha = 0.5 per sample of d = 0.5: rho = ln 2 / 0.5 = 1.386294361119891.
  CHECK(std::fabs(rayint::density_from_opacity(0.5, OpacityConvention::sample_distance, 0.5) -
                  1.3862943611198906) <= 4e-16);
  // A sample of length d with that density has opacity 1 - e^{-rho d} = alpha again.
  const double a = 0.37, dd = 0.02;
  CHECK(std::fabs(-std::expm1(-rayint::density_from_opacity(a, OpacityConvention::sample_distance, dd) * dd) - a) <= 1e-16);
}

TEST_CASE("a case file may reference a preset, resolved against the case file", "[tf]") {
  rayint::test::TempDir dir;
  fs::create_directories(dir.path / "sub");
  fs::copy_file(kData / "exported-opacity.json", dir.path / "sub" / "presets.json");
  dir.write("case.json", R"j({"name": "preset-case",
    "transfer_function": {"paraview_preset": "sub/presets.json", "name": "rayint midpoints (sharpness 0)",
                          "unit_distance": 0.25},
    "rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]}]})j");
  const rayint::Case c = rayint::read_case_file((dir.path / "case.json").string());
  const rayint::PresetImport imp = import("rayint midpoints (sharpness 0)", OpacityConvention::unit_distance, 0.25, 1e-6);
  CHECK(c.transfer.density[0].scalar == imp.result.transfer.density[0].scalar);
  CHECK(c.transfer.density[0].value == imp.result.transfer.density[0].value);
  CHECK(c.transfer.color[2].value == imp.result.transfer.color[2].value);
  CHECK(c.transfer.density[0](0.125) == 0.8);  // 0.2 per unit distance 0.25

  dir.write("bad.json", R"j({"name": "x", "transfer_function": {"paraview_preset": "sub/presets.json",
    "name": "rayint midpoints (sharpness 0)", "sample_distance": 0}, "rays": [{"segments": [{"length": 1, "scalar": [0, 1]}]}]})j");
  CHECK_THROWS_WITH(rayint::read_case_file((dir.path / "bad.json").string()),
                    Catch::Contains("bad.json: transfer_function.sample_distance: must be finite and > 0"));
}

TEST_CASE("tf import: output, report, and bad input (exit 2, one line naming file and field, nothing written)", "[tf][cli]") {
  using rayint::test::run_cli;
  rayint::test::TempDir dir;
  fs::copy_file(kData / "paraview-colormaps.json", dir.path / "maps.json");
  fs::copy_file(kData / "exported-opacity.json", dir.path / "exported.json");

  const auto ok = run_cli(dir.path, "tf import exported.json --name 'rayint sharpness' --unit-distance 2 "
                                    "--tolerance 1e-5 -o tf.json --report report.json");
  REQUIRE(ok.status == 0);
  const nlohmann::json report = nlohmann::json::parse(rayint::test::slurp(dir.path / "report.json"));
  CHECK(report["convention"] == "unit_distance");
  CHECK(report["density"]["max_deviation"].get<double>() <= report["density"]["tolerance"].get<double>());
  CHECK(report["density"]["linearised_intervals"].get<int>() == 3);  // sharpness .3, .7, .5
  CHECK(report["density"]["exact_intervals"].get<int>() == 1);       // the step
  CHECK(ok.err.find("linearised; measured max deviation") != std::string::npos);
  // The written object is a case file's transfer_function: it reads back through a case.
  dir.write("case.json", "{\"name\": \"c\", \"transfer_function\": " + rayint::test::slurp(dir.path / "tf.json") +
                             ", \"rays\": [{\"segments\": [{\"length\": 1, \"scalar\": [-1, 1]}]}]}");
  CHECK_NOTHROW(rayint::read_case_file((dir.path / "case.json").string()));

  const std::set<std::string> before = dir.entries();
  struct Bad {
    std::string file, args, expect;
  };
  dir.write("alpha1.json", preset_text("a", {0, 1, 1, 1, 1, 1, 1, 1}, {0, 0.2, 0.5, 0, 1, 1.0, 0.5, 0}));
  dir.write("count.json", R"([{"Name": "c", "ColorSpace": "RGB", "RGBPoints": [0, 1, 1], "Points": [0, 1, 0.5, 0]}])");
  dir.write("space.json", R"({"Name": "c", "ColorSpace": "CIELab", "RGBPoints": [0, 1, 1, 1]})");
  dir.write("log.json", R"({"Name": "c", "ColorSpace": "RGB", "UseLogScale": 1, "RGBPoints": [0, 1, 1, 1, 1, 0, 0, 0]})");
  dir.write("cat.json", R"({"Name": "c", "IndexedColors": [1, 0, 0, 0, 1, 0], "Annotations": ["0", "a", "1", "b"]})");
  dir.write("rgb.json", R"({"Name": "c", "ColorSpace": "RGB", "RGBPoints": [0, 1, 1.5, 1]})");
  dir.write("order.json", R"({"Name": "c", "ColorSpace": "RGB", "RGBPoints": [1, 1, 1, 1, 0, 0, 0, 0], "Points": [0, 1, 0.5, 0]})");
  dir.write("mid.json", R"({"Name": "c", "ColorSpace": "RGB", "RGBPoints": [0, 1, 1, 1], "Points": [0, 1, 1.5, 0]})");
  dir.write("syntax.json", R"([{"Name": "c",)");
  const std::set<std::string> inputs = dir.entries();
  for (const Bad& b : {Bad{"alpha1.json", "--sample-distance 0.5", "alpha1.json: [0].Points[5]: opacity 1 per sample is fully opaque"},
                       Bad{"count.json", "", "count.json: [0].RGBPoints: must be a flat list of [x, r, g, b] tuples"},
                       Bad{"space.json", "--opacity 0.5", "space.json: ColorSpace: unknown colour space \"CIELab\""},
                       Bad{"log.json", "", "log.json: UseLogScale: a log scale needs scalars > 0, and the first RGBPoints scalar is 0"},
                       Bad{"cat.json", "", "cat.json: IndexedColors: a categorical colour map (IndexedColors): categorical maps have no continuous transfer function"},
                       Bad{"rgb.json", "", "rgb.json: RGBPoints[2]: colour components must be in [0, 1]"},
                       Bad{"maps.json", "--name Viridis --sample-distance 1", "maps.json: [1].Points: missing, and the default opacity (ParaView's ramp 0 -> 1) reaches 1"},
                       Bad{"order.json", "", "order.json: RGBPoints[4]: scalars must be non-decreasing (0 after 1)"},
                       Bad{"mid.json", "", "mid.json: Points[2]: must be in [0, 1]"},
                       Bad{"syntax.json", "", "syntax.json: "},
                       Bad{"maps.json", "", "maps.json: (root): holds 6 presets: name one (--name)"},
                       Bad{"maps.json", "--name Nope --opacity 0.5", "no preset named \"Nope\""},
                       Bad{"maps.json", "--name Viridis --opacity 1 --sample-distance 1", "rayint tf import: --opacity: opacity 1 per sample"}}) {
    INFO(b.file << " " << b.args);
    const auto r = run_cli(dir.path, "tf import " + b.file + " " + b.args + " -o out.json --report rep.json");
    rayint::test::check_usage_error(r);
    CHECK(r.err.find(b.expect) != std::string::npos);
    CHECK(dir.entries() == inputs);
  }
  (void)before;
}
