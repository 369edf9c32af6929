// `rayint render SCENE --loss-target T --grad-out G` on voxel-grid scenes (issue 28, images;
// cli/render_scene_gradient.cpp, scene/grid_loss_gradient.hpp): the NPY the CLI writes against
// an independent reference, fourth-order central differences of the loss formed from the
// 50-digit reference render (reference_poly_ray on the trilinear cubics, reference_ray on the Kuhn
// segments) of the perturbed grid, for every grid point; wrong gradients (the other
// interpolant's, the array read in the wrong axis order) caught by the same comparison; bad input
// one line and exit 2; an undefined derivative exit 1; nothing written in either case.
//
// The reference is built from the test's own numbers (grid, transfer functions, camera), not
// from the scene the CLI reads, and shares nothing with the gradient code but the cube walk that
// turns a grid into cubics (trilinear_ray) or segments (ray_segments), which the 50-digit
// integral needs as input.
//
// Difference step h = 1e-5 (tests/test_trilinear_grad.cpp: at 1e-4 a near-tangency of a cube's
// cubic with a breakpoint spoiled the differences there); the perturbed cubics are rounded to
// double (~1e-16), which the quotient turns into ~1e-11 of the gradient. Tolerance 1e-8 of the
// largest |entry|, as the library's trilinear test.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cli_harness.hpp"
#include "rayint/geometry/camera.hpp"
#include "rayint/grid/voxel_grid.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/render/float_image.hpp"

using namespace rayint;
using rayint::test::run_cli;
using rayint::test::slurp;
using rayint::test::TempDir;
using nlohmann::json;

namespace {

constexpr double kStep = 1e-5;
constexpr double kTol = 1e-8;

// The test's medium: a 4 x 3 x 3 grid of values in [0, 1], extinction with kinks per channel,
// emission per channel, a grey-blue background.
struct GridScene {
  std::array<int, 3> dims{{4, 3, 3}};
  Vec3 origin{-1.0, -0.5, -0.7};
  Vec3 spacing{0.6, 0.55, 0.7};
  std::vector<double> values;
  TransferFunctions tf;  // density = extinction, color = emission
  Rgb background{0.2, 0.1, 0.4};
  bool kuhn = false;
  Camera camera;
  std::vector<ViewRay> rays;  // non-empty: explicit rays instead of the camera

  VoxelGrid grid(const std::vector<double>& v) const { return VoxelGrid(dims, origin, spacing, v); }
  int width() const { return rays.empty() ? camera.width : static_cast<int>(rays.size()); }
  int height() const { return rays.empty() ? camera.height : 1; }
  ViewRay ray(int x, int y) const { return rays.empty() ? camera.ray_for_pixel(x, y) : rays[static_cast<std::size_t>(x)]; }
};

GridScene make_scene(bool kuhn, bool explicit_rays) {
  GridScene s;
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  s.values.resize(4 * 3 * 3);
  for (double& v : s.values) v = u(rng);
  const std::vector<double> x = {0.1, 0.35, 0.6, 0.9};
  s.tf.density[0] = {x, {0.5, 2.0, 0.7, 1.5}};
  s.tf.density[1] = {x, {1.0, 0.2, 2.5, 0.1}};
  s.tf.density[2] = {{0.2, 0.7}, {0.3, 3.0}};
  s.tf.color[0] = {x, {0.1, 0.9, 0.4, 1.0}};
  s.tf.color[1] = {{0.15, 0.65}, {1.0, 0.2}};
  s.tf.color[2] = {x, {0.6, 0.3, 1.2, 0.5}};
  s.kuhn = kuhn;
  s.camera.position = Vec3(0.37, -0.21, 4.0);
  s.camera.look_at = Vec3(-0.07, 0.05, 0.0);
  s.camera.fov_deg = 20.0;
  s.camera.width = 5;
  s.camera.height = 4;
  if (explicit_rays) {
    const auto toward = [](const Vec3& from, const Vec3& to) { return ViewRay{from, (to - from).normalized()}; };
    const VoxelGrid g = s.grid(s.values);
    const Vec3 lo = g.lower(), hi = g.upper(), sp = g.spacing();
    s.rays = {toward({-2.3, -1.7, -3.1}, {0.31, 0.22, 0.17}),
              // along a grid line (in two grid planes), through grid points
              toward(Vec3(lo.x() - 1.0, lo.y() + sp.y(), lo.z() + sp.z()), Vec3(hi.x(), lo.y() + sp.y(), lo.z() + sp.z())),
              // through grid points along a cube diagonal
              toward(lo - sp, lo + 2.0 * sp),
              // from inside the grid
              ViewRay{Vec3(0.1, 0.05, 0.0), Vec3(0.3, 0.5, 0.81).normalized()}};
  }
  return s;
}

json channels_json(const std::array<PiecewiseLinear, kChannels>& f) {
  json out;
  const char* names[] = {"r", "g", "b"};
  for (int c = 0; c < kChannels; ++c) {
    json pts = json::array();
    for (std::size_t k = 0; k < f[static_cast<std::size_t>(c)].scalar.size(); ++k)
      pts.push_back({f[static_cast<std::size_t>(c)].scalar[k], f[static_cast<std::size_t>(c)].value[k]});
    out[names[c]] = pts;
  }
  return out;
}

json vec_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

std::string scene_text(const GridScene& s) {
  json grid = {{"dims", s.dims}, {"origin", vec_json(s.origin)}, {"spacing", vec_json(s.spacing)}, {"values", s.values}};
  json medium = {{"type", "grid"}, {"grid", grid}};
  if (s.kuhn) medium["interpolation"] = "kuhn";
  json j = {{"medium", medium},
            {"transfer", {{"extinction", channels_json(s.tf.density)}, {"emission", channels_json(s.tf.color)}}},
            {"background", {{"color", {s.background[0], s.background[1], s.background[2]}}}},
            {"effects", {"absorption", "emission"}}};
  if (s.rays.empty()) {
    j["camera"] = {{"position", vec_json(s.camera.position)}, {"look_at", vec_json(s.camera.look_at)},
                   {"fov_deg", s.camera.fov_deg}, {"width", s.camera.width}, {"height", s.camera.height}};
  } else {
    j["rays"] = json::array();
    for (const ViewRay& r : s.rays) j["rays"].push_back({{"origin", vec_json(r.origin)}, {"direction", vec_json(r.direction)}});
  }
  return j.dump();
}

// The target: a grey image with one pixel away from it.
Image target_for(const GridScene& s) {
  Image t(s.width(), s.height(), Rgb{0.3, 0.5, 0.2});
  t.at(s.width() / 2, s.height() / 2) = Rgb{0.9, 0.1, 0.0};
  return t;
}

// The 50-digit reference pixel of the grid with values `v`, in the scene's interpolation.
Rgb reference_pixel(const GridScene& s, const std::vector<double>& v, const ViewRay& view) {
  const VoxelGrid g = s.grid(v);
  const ReferenceRay r = s.kuhn ? reference_ray(s.tf, ray_segments(g, view, s.background))
                                : reference_poly_ray(s.tf, trilinear_ray(g, view, s.background));
  Rgb out{};
  for (int c = 0; c < kChannels; ++c) out[c] = r.intensity[c].hi + r.intensity[c].lo;
  return out;
}

double pixel_loss(const Rgb& i, const Rgb& t) {
  double l = 0.0;
  for (int c = 0; c < kChannels; ++c) l += (i[c] - t[c]) * (i[c] - t[c]);
  return l;
}

// dloss / d value of every grid point: per pixel, the fourth-order central difference of the
// pixel's loss, summed.
std::vector<double> reference_loss_gradient(const GridScene& s, const Image& target) {
  std::vector<double> out(s.values.size(), 0.0);
  for (std::size_t i = 0; i < s.values.size(); ++i)
    for (int y = 0; y < s.height(); ++y)
      for (int x = 0; x < s.width(); ++x) {
        const auto at = [&](double h) {
          std::vector<double> v = s.values;
          v[i] += h;
          return pixel_loss(reference_pixel(s, v, s.ray(x, y)), target.at(x, y));
        };
        out[i] += (at(-2 * kStep) - 8 * at(-kStep) + 8 * at(kStep) - at(2 * kStep)) / (12 * kStep);
      }
  return out;
}

// A float64 NPY's header dict and values.
std::pair<std::string, std::vector<double>> read_npy(const std::string& npy) {
  REQUIRE(npy.size() >= 10);
  const std::size_t header = 10 + static_cast<unsigned char>(npy[8]) + 256u * static_cast<unsigned char>(npy[9]);
  std::vector<double> v((npy.size() - header) / 8);
  std::memcpy(v.data(), npy.data() + header, v.size() * 8);
  return {npy.substr(10, header - 10), v};
}

// max |got - want| / max |want|.
double worst_rel(const std::vector<double>& got, const std::vector<double>& want) {
  double scale = 0.0, worst = 0.0;
  for (double w : want) scale = std::max(scale, std::fabs(w));
  for (std::size_t i = 0; i < want.size(); ++i) worst = std::max(worst, std::fabs(got[i] - want[i]));
  return worst / scale;
}

double loss_printed(const std::string& err) {
  const std::string key = "rayint render: loss ";
  const auto at = err.find(key);
  return at == std::string::npos ? -1.0 : std::stod(err.substr(at + key.size()));
}

// Writes the scene and target, runs the CLI; returns (gradient values, stderr).
struct GradRun {
  int status = -1;
  std::string err, header;
  std::vector<double> gradient;
  Image image;
};
GradRun run_gradient(const TempDir& dir, const GridScene& s, const Image& target) {
  dir.write("scene.json", scene_text(s));
  dir.write("target.npy", encode_npy(target));
  const auto r = run_cli(dir.path, "render scene.json -o img.npy --loss-target target.npy --grad-out g.npy -q");
  GradRun out;
  out.status = r.status;
  out.err = r.err;
  if (r.status != 0) return out;
  std::tie(out.header, out.gradient) = read_npy(slurp(dir.path / "g.npy"));
  out.image = read_image((dir.path / "img.npy").string());
  return out;
}

}  // namespace

TEST_CASE("render --grad-out on a voxel-grid scene against differences of the 50-digit loss, wrong gradients caught",
          "[grad][grad_cli][grid_grad_cli]") {
  std::vector<double> trilinear_want, trilinear_got, kuhn_got;  // camera, for the wrong candidates
  for (const bool kuhn : {false, true})
    for (const bool explicit_rays : {false, true}) {
      const GridScene s = make_scene(kuhn, explicit_rays);
      const Image target = target_for(s);
      TempDir dir;
      const GradRun run = run_gradient(dir, s, target);
      INFO(run.err);
      REQUIRE(run.status == 0);
      const std::string interp = kuhn ? "kuhn" : "trilinear";
      CHECK(run.err.find("d loss / d grid point value (" + interp + " interpolation) -> g.npy (shape (nz, ny, nx) = "
                         "(3, 3, 4), x fastest as the grid's values)") != std::string::npos);
      CHECK(run.header.find("'fortran_order': False, 'shape': (3, 3, 4)") != std::string::npos);
      REQUIRE(run.gradient.size() == s.values.size());
      // The image: the reference render to the integral's accuracy; the loss printed: its loss.
      REQUIRE(run.image.width == s.width());
      REQUIRE(run.image.height == s.height());
      double image_err = 0.0, ref_loss = 0.0;
      for (int y = 0; y < s.height(); ++y)
        for (int x = 0; x < s.width(); ++x) {
          const Rgb want = reference_pixel(s, s.values, s.ray(x, y));
          ref_loss += pixel_loss(want, target.at(x, y));
          for (int c = 0; c < kChannels; ++c) image_err = std::max(image_err, std::fabs(run.image.at(x, y)[c] - want[c]));
        }
      CHECK(image_err <= 1e-14);
      CHECK(std::fabs(loss_printed(run.err) - ref_loss) <= 1e-12 * ref_loss);
      // The plain render writes the same image (to rounding: B T + E summed vs composited).
      REQUIRE(run_cli(dir.path, "render scene.json -o plain.npy -q").status == 0);
      const Image plain = read_image((dir.path / "plain.npy").string());
      double plain_err = 0.0;
      for (std::size_t p = 0; p < plain.pixels.size(); ++p)
        for (int c = 0; c < kChannels; ++c)
          plain_err = std::max(plain_err, std::fabs(plain.pixels[p][c] - run.image.pixels[p][c]));
      CHECK(plain_err <= 1e-13);
      // The gradient, every grid point.
      const std::vector<double> want = reference_loss_gradient(s, target);
      const double err = worst_rel(run.gradient, want);
      std::size_t nonzero = 0;
      for (double w : want) nonzero += w != 0.0;
      WARN(interp << (explicit_rays ? ", 4 explicit rays" : ", camera 5 x 4") << ": d loss / d value of " << want.size()
                  << " grid points (" << nonzero << " non-zero) vs differences of the 50-digit loss: worst " << err
                  << " of the largest entry; image vs reference " << image_err << ", vs plain render " << plain_err);
      CHECK(nonzero >= 20u);  // the rays see most of the grid
      CHECK(err <= kTol);
      if (explicit_rays) continue;
      (kuhn ? kuhn_got : trilinear_got) = run.gradient;
      if (!kuhn) trilinear_want = want;
    }
  // Wrong gradients, by the same comparison: the Kuhn interpolant's offered for the trilinear
  // render (same grid, camera and target), and the right array read in the wrong axis order
  // (point (i, j, k) taken from [i, j, k] of a (nx, ny, nz) C-order reading: z fastest).
  std::vector<double> swapped(trilinear_got.size());
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i)
        swapped[static_cast<std::size_t>(i + 4 * (j + 3 * k))] = trilinear_got[static_cast<std::size_t>(k + 3 * (j + 3 * i))];
  const double right_err = worst_rel(trilinear_got, trilinear_want), kuhn_err = worst_rel(kuhn_got, trilinear_want),
               swapped_err = worst_rel(swapped, trilinear_want);
  WARN("trilinear loss gradient " << right_err << "; the Kuhn gradient as its candidate " << kuhn_err
                                  << "; read in the wrong axis order " << swapped_err);
  CHECK(right_err <= kTol);
  CHECK(kuhn_err > 1e-2);
  CHECK(swapped_err > 1e-2);
}

TEST_CASE("render --grad-out on a scene: bad input is one line naming the file and field, exit 2, nothing written",
          "[grad][grad_cli][grid_grad_cli]") {
  const GridScene s = make_scene(false, false);
  TempDir dir;
  const std::string scene = scene_text(s);
  dir.write("scene.json", scene);
  dir.write("target.npy", encode_npy(target_for(s)));
  dir.write("small.npy", encode_npy(Image(4, 4)));
  dir.write("t.png", "not read");
  json j = json::parse(scene);
  j["effects"] = {"emission"};
  dir.write("emission_only.json", j.dump());
  j["effects"] = {"absorption", "emission"};
  j["medium"] = {{"type", "homogeneous"}, {"shape", "box"}, {"lower", {-1, -1, -1}}, {"upper", {1, 1, 1}}, {"density", 0.5}};
  dir.write("homogeneous.json", j.dump());
  const std::set<std::string> inputs = dir.entries();
  const struct {
    std::string args, message;
  } cases[] = {
      {"scene.json -o x.npy --loss-target small.npy --grad-out g.npy",
       "rayint: error: small.npy: --loss-target: the image is 4 x 4, the scene renders 5 x 4\n"},
      {"scene.json -o x.npy --loss-target t.png --grad-out g.npy",
       "rayint: error: t.png: --loss-target: a float image is needed (.npy, .pfm, .exr), not 8-bit PNG\n"},
      {"scene.json -o x.npy --loss-target missing.npy --grad-out g.npy", "missing.npy"},
      {"scene.json -o x.npy --loss-target target.npy --grad-out g.npy --grad-positions-out p.npy",
       "rayint: error: scene.json: medium: --grad-positions-out is for mesh cases (grid point positions are fixed "
       "by origin and spacing and not differentiated)\n"},
      {"emission_only.json -o x.npy --loss-target target.npy --grad-out g.npy",
       "rayint: error: emission_only.json: effects: --grad-out differentiates the emission-absorption image "
       "(\"absorption\", optionally with \"emission\"); \"absorption\" is not named\n"},
      {"homogeneous.json -o x.npy --loss-target target.npy --grad-out g.npy",
       "rayint: error: homogeneous.json: medium.type: --grad-out differentiates a voxel grid (\"grid\"), not "},
      {"scene.json -o x.npy --loss-target target.npy --grad-out g.npy --method absorption=riemann:n=8",
       "rayint: error: scene.json: methods.absorption: --grad-out differentiates the exact method, not riemann:n=8\n"},
      {"scene.json -o x.npy --loss-target target.npy --grad-out g.npy --errors 2",
       "rayint: error: --grad-out: not with --compare, --shard, --stats, --fit or --errors\n"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(dir.path, "render " + c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    if (c.message.back() == '\n') CHECK(r.err == c.message);
    else CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(dir.entries() == inputs);
  }
}

TEST_CASE("render --grad-out on a voxel-grid scene: an undefined derivative fails the run, nothing written",
          "[grad][grad_cli][grid_grad_cli]") {
  // Extinction jumps at 0.5; the grid is 0.25 i (linear in x), so the cube face x = 1 holds 0.5
  // exactly. A ray crossing it meets the jump on a cube face, where the crossing's derivative
  // does not exist (docs/gradients.md, "Jumps": the one-sided derivatives differ).
  GridScene s = make_scene(false, true);
  s.origin = Vec3(0.0, 0.0, 0.0);
  s.spacing = Vec3(0.5, 0.5, 0.5);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) s.values[static_cast<std::size_t>(i + 4 * (j + 3 * k))] = 0.25 * i;
  s.tf.density[0] = {{0.0, 0.5, 0.5, 1.0}, {0.5, 1.0, 2.0, 1.0}};
  // Ray 0 crosses x = 1 (a cube face on the jump); ray 1 stays below 0.5.
  s.rays = {ViewRay{Vec3(-1.0, 0.3, 0.4), Vec3(1.0, 0.1, 0.2)}, ViewRay{Vec3(0.2, 0.3, 0.4), Vec3(-1.0, 0.1, 0.2)}};
  TempDir dir;
  dir.write("scene.json", scene_text(s));
  dir.write("target.npy", encode_npy(Image(2, 1)));
  const auto r = run_cli(dir.path, "render scene.json -o img.npy --loss-target target.npy --grad-out g.npy");
  INFO(r.err);
  CHECK(r.status == 1);
  CHECK(r.err.rfind("rayint render: 1 pixels failed (non-finite intensity or derivative; first pixel (0, 0): the ray "
                    "touches the jump of density r at a cube face", 0) == 0);
  CHECK(r.err.find("); no gradient written\n") == r.err.size() - 23);
  CHECK(dir.entries() == std::set<std::string>{"scene.json", "target.npy"});
}
