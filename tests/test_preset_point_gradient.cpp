// Gradients with respect to a ParaView preset's own points (model/preset_point_gradient.hpp,
// issue 28): the chain rule through the import against central differences of the whole
// pipeline (points -> import_vtk_transfer_function -> exact intensity), and the cases where the
// import is not differentiable reported as unavailable.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/model/preset_point_gradient.hpp"

using namespace rayint;

namespace {

// RGB with a two-piece interval (midpoint 0.3) and, with `step`, a step (sharpness 1: imported as
// a true jump); opacity with a two-piece interval (midpoint 0.7).
PresetCurves test_curves(OpacityConvention convention = OpacityConvention::unit_distance, bool step = false) {
  PresetCurves p;
  p.color.space = VtkColorSpace::rgb;
  p.color.nodes = {{0.0, {0.1, 0.2, 0.9}, 0.5, 0.0},
                   {0.35, {0.8, 0.3, 0.2}, 0.3, 0.0},
                   {0.6, {0.4, 0.9, 0.1}, 0.5, step ? 1.0 : 0.0},
                   {1.0, {0.9, 0.6, 0.5}, 0.5, 0.0}};
  p.opacity.nodes = {{0.0, 0.1, 0.5, 0.0}, {0.45, 0.6, 0.7, 0.0}, {1.0, 0.3, 0.5, 0.0}};
  p.options.convention = convention;
  p.options.distance = 2.0;
  return p;
}

Ray test_ray() {
  Ray ray;
  ray.background = {0.3, 0.1, 0.6};
  ray.segments = {{0.7, 0.0123, 0.8871}, {0.45, 0.8871, 0.3317}, {1.3, 0.3317, 0.9533}};
  return ray;
}

Rgb intensity(const PresetCurves& p, const Ray& ray) {
  const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
  return make_integrator(parse_method_spec("exact"), imp.transfer)->integrate(ray, nullptr).intensity;
}

}  // namespace

TEST_CASE("preset point gradient: the chain rule through the import matches differences of the pipeline",
          "[grad][preset_grad]") {
  const Ray ray = test_ray();
  // With `step`, interval 2 is a step (a true jump at 0.8, which the ray crosses three times):
  // its position and its two values reach the points through the jump's gradient.
  for (const bool step : {false, true})
  for (const bool rescaled : {false, true}) {
    PresetCurves p = test_curves(OpacityConvention::unit_distance, step);
    PresetCurves base = p;  // the points before any rescaling (what the differences perturb)
    if (rescaled) {  // to [2, 5]: X' = 2 + 3 X
      p.rescale = std::array<double, 4>{0.0, 1.0, 2.0, 5.0};
      for (auto& n : p.color.nodes) n.x = 2.0 + 3.0 * n.x;
      for (auto& n : p.opacity.nodes) n.x = 2.0 + 3.0 * n.x;
    }
    Ray r = ray;
    if (rescaled)
      for (auto& s : r.segments) s.scalar_far = 2.0 + 3.0 * s.scalar_far, s.scalar_exit = 2.0 + 3.0 * s.scalar_exit;
    const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
    REQUIRE(imp.transfer.has_jump() == step);
    REQUIRE(imp.color.exact());
    REQUIRE(imp.density.exact());
    const PresetPointGradient pg = preset_point_gradient(p, imp, exact_ray_gradient(imp.transfer, r));
    REQUIRE(pg.color_ok);
    REQUIRE(pg.opacity_ok);
    // The pipeline with the rescaling applied to perturbed points (a0 = X_0, a1 = X_n move too).
    const auto pipeline = [&](PresetCurves q) {
      if (rescaled) {
        const double a0 = q.color.nodes.front().x, a1 = q.color.nodes.back().x;
        for (auto& n : q.color.nodes) n.x = 2.0 + (n.x - a0) * 3.0 / (a1 - a0);
        for (auto& n : q.opacity.nodes) n.x = 2.0 + (n.x - a0) * 3.0 / (a1 - a0);
      }
      return intensity(q, r);
    };
    const auto difference = [&](auto&& pick) {
      PresetCurves q = base;
      double& x = pick(q);
      const double x0 = x, h = 1e-6;
      x = x0 + h;
      const Rgb up = pipeline(q);
      x = x0 - h;
      const Rgb down = pipeline(q);
      Rgb d{};
      for (int c = 0; c < kChannels; ++c) d[c] = (up[c] - down[c]) / (2 * h);
      return d;
    };
    double scale[kChannels] = {0.0, 0.0, 0.0};
    for (int c = 0; c < kChannels; ++c) {
      for (const auto& e : pg.rgb_points[static_cast<std::size_t>(c)])
        for (double v : e) scale[c] = std::max(scale[c], std::fabs(v));
      for (const auto& e : pg.points[static_cast<std::size_t>(c)])
        for (double v : e) scale[c] = std::max(scale[c], std::fabs(v));
      REQUIRE(scale[c] > 0.0);
    }
    double worst = 0.0;
    // Every entry `what` of node k of the preset's array `name` (`nodes` nodes of `entries`
    // numbers; `entry` picks it in a PresetCurves) against the central difference.
    const auto check_array = [&](const char* name, std::size_t nodes, int entries, const auto& got_table, auto&& entry) {
      for (std::size_t k = 0; k < nodes; ++k) {
        for (int what = 0; what < entries; ++what) {
          const Rgb d = difference([&](PresetCurves& q) -> double& { return entry(q, k, what); });
          for (int c = 0; c < kChannels; ++c) {
            const double got = got_table[static_cast<std::size_t>(c)][k][static_cast<std::size_t>(what)];
            INFO("rescaled " << rescaled << " " << name << "[" << k << "] entry " << what << " channel " << c << ": "
                             << got << " vs " << d[c]);
            CHECK(std::fabs(got - d[c]) <= 1e-7 * scale[c]);
            worst = std::max(worst, std::fabs(got - d[c]) / scale[c]);
          }
        }
      }
    };
    check_array("RGBPoints", base.color.nodes.size(), 4, pg.rgb_points, [](PresetCurves& q, std::size_t k, int what) -> double& {
      return what == 0 ? q.color.nodes[k].x : q.color.nodes[k].rgb[what - 1];
    });
    check_array("Points", base.opacity.nodes.size(), 2, pg.points, [](PresetCurves& q, std::size_t k, int what) -> double& {
      return what == 0 ? q.opacity.nodes[k].x : q.opacity.nodes[k].y;
    });
    WARN("preset point gradient vs central differences (h = 1e-6) of the import + exact pipeline, step "
         << step << ", rescaled " << rescaled << ": worst " << worst << " of the channel's largest entry");
  }
}

TEST_CASE("preset point gradient: where the import is not differentiable it says so", "[grad][preset_grad]") {
  const Ray ray = test_ray();
  {  // HSV: the colour is linearised adaptively
    PresetCurves p = test_curves();
    p.color.space = VtkColorSpace::hsv;
    const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
    const PresetPointGradient pg = preset_point_gradient(p, imp, exact_ray_gradient(imp.transfer, ray));
    CHECK_FALSE(pg.color_ok);
    CHECK(pg.color_unavailable.find("adaptively") != std::string::npos);
    CHECK(pg.rgb_points[0].empty());
    CHECK(pg.opacity_ok);  // the opacity still is
  }
  {  // sample_distance: -ln(1 - y)/d
    PresetCurves p = test_curves(OpacityConvention::sample_distance);
    const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
    const PresetPointGradient pg = preset_point_gradient(p, imp, exact_ray_gradient(imp.transfer, ray));
    CHECK(pg.color_ok);
    CHECK_FALSE(pg.opacity_ok);
    CHECK(pg.opacity_unavailable.find("sample_distance") != std::string::npos);
    CHECK(pg.points[0].empty());
  }
  {  // a curved opacity interval (sharpness 0.5)
    PresetCurves p = test_curves();
    p.opacity.nodes[0].sharpness = 0.5;
    const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
    const PresetPointGradient pg = preset_point_gradient(p, imp, exact_ray_gradient(imp.transfer, ray));
    CHECK_FALSE(pg.opacity_ok);
    CHECK(pg.opacity_unavailable.find("adaptively") != std::string::npos);
  }
}

TEST_CASE("preset point gradient: a preset step is a jump, differentiated with the tie convention", "[grad][preset_grad]") {
  const PresetCurves p = test_curves(OpacityConvention::unit_distance, true);
  const TfImport imp = import_vtk_transfer_function(p.color, p.opacity, p.options);
  REQUIRE(imp.transfer.has_jump());
  const RayGradient g = exact_ray_gradient(imp.transfer, test_ray());
  CHECK(g.undefined.empty());
  // The jump's two imported nodes: the first carries the position derivative, the second 0.
  const PiecewiseLinear& f = imp.transfer.color[0];
  int jumps = 0;
  for (std::size_t i = 0; i + 1 < f.scalar.size(); ++i)
    if (f.scalar[i] == f.scalar[i + 1]) {
      ++jumps;
      CHECK(g.color[0][i].position != 0.0);
      CHECK(g.color[0][i + 1].position == 0.0);
    }
  CHECK(jumps == 1);
}
