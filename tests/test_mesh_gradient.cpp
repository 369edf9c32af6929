// Mesh gradients (issue 28, meshes): render/mesh_gradient.* against fourth-order central
// differences of the 50-digit reference render (reference_ray on the perturbed mesh, retraced),
// on small jittered Kuhn boxes: the pixel Jacobian w.r.t. vertex scalars (rays through vertices
// included), vertex positions (face crossings, the eye inside a cell), cell data, and the
// gradient of an image loss. A deliberately wrong candidate is caught by the same comparison.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "rayint/integrators/exact_grad.hpp"
#include "rayint/mesh/gradients.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/render/mesh_gradient.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

namespace {

// Tolerances (relative to the largest |entry| of the pixel's channel). The differences' own
// error: traversal rounds t and s to ~1e-16, divided by the step (1e-4 for scalars, 1e-4 of the
// cell size for positions) ~1e-12, times the stencil's 1.5; truncation h^4 I^(5) ~1e-16.
// Measured worst (WARN lines): 2.7e-12 scalars, 6.4e-12 positions, 1.6e-11 the image loss.
constexpr double kScalarTol = 1e-10;
constexpr double kPositionTol = 1e-10;

TetMesh small_mesh(std::uint64_t seed) {
  const Vec3 lo(-1, -1, -1), hi(1, 1, 1);
  TetMesh m = structured_box_mesh(lo, hi, 2, 2, 2);  // 48 tets, 27 points
  jitter_interior(m, lo, hi, 2, 0.2, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.6, 1.0);
  for (double& v : m.scalars) v = u(rng);
  return m;
}

Rgb reference_pixel(const TetMesh& m, const TransferFunctions& tf, const ViewRay& view, const Rgb& bg) {
  const TetTraversal t(m);
  const ReferenceRay r = reference_ray(tf, mesh_ray(t, view, bg));
  return {r.intensity[0].hi + r.intensity[0].lo, r.intensity[1].hi + r.intensity[1].lo,
          r.intensity[2].hi + r.intensity[2].lo};
}

// Fourth-order central difference of f(perturbed mesh) in one parameter.
Rgb central_difference(const std::function<Rgb(double)>& f, double h) {
  const Rgb m2 = f(-2 * h), m1 = f(-h), p1 = f(h), p2 = f(2 * h);
  Rgb d{};
  for (int c = 0; c < kChannels; ++c) d[c] = (m2[c] - 8 * m1[c] + 8 * p1[c] - p2[c]) / (12 * h);
  return d;
}

struct Compare {
  double worst = 0.0;
  std::string where;
  long entries = 0;
  void add(const Rgb& got, const Rgb& want, const Rgb& scale, const std::string& label) {
    for (int c = 0; c < kChannels; ++c) {
      const double e = std::fabs(got[c] - want[c]) / (scale[c] > 0 ? scale[c] : 1.0);
      ++entries;
      if (!(e <= worst)) {
        worst = e;
        where = label + " channel " + std::to_string(c);
      }
    }
  }
  // Another comparison folded in: its worst if that is worse (or NaN), its entries added.
  void merge(const Compare& c) {
    if (!(c.worst <= worst)) {
      worst = c.worst;
      where = c.where;
    }
    entries += c.entries;
  }
};

Rgb lookup_scalar(const PixelJacobian& j, std::int32_t i) {
  const auto it = std::lower_bound(j.index.begin(), j.index.end(), i);
  return it != j.index.end() && *it == i ? j.d_scalar[static_cast<std::size_t>(it - j.index.begin())] : Rgb{};
}
Rgb lookup_position(const PixelJacobian& j, std::int32_t i, int axis) {
  const auto it = std::lower_bound(j.position_index.begin(), j.position_index.end(), i);
  return it != j.position_index.end() && *it == i
             ? j.d_position[static_cast<std::size_t>(it - j.position_index.begin())][static_cast<std::size_t>(axis)]
             : Rgb{};
}

// The scalar Jacobian of every vertex against central differences of the reference pixel.
Compare check_scalars(const TetMesh& m, const TransferFunctions& tf, const ViewRay& view, const Rgb& bg,
                      const PixelJacobian& got, const std::string& label) {
  Rgb scale{};
  for (int c = 0; c < kChannels; ++c) scale[c] = got.channel_scale(c);
  const bool cells = !m.cell_scalars.empty();
  const std::size_t n = cells ? m.cell_scalars.size() : m.scalars.size();
  Compare cmp;
  for (std::size_t i = 0; i < n; ++i) {
    const Rgb want = central_difference([&](double dv) {
      TetMesh p = m;
      (cells ? p.cell_scalars : p.scalars)[i] += dv;
      return reference_pixel(p, tf, view, bg);
    }, 1e-4);
    cmp.add(lookup_scalar(got, static_cast<std::int32_t>(i)), want, scale, label + " scalar " + std::to_string(i));
  }
  return cmp;
}

Compare check_positions(const TetMesh& m, const TransferFunctions& tf, const ViewRay& view, const Rgb& bg,
                        const PixelJacobian& got, const std::string& label) {
  Rgb scale{};
  for (int c = 0; c < kChannels; ++c) scale[c] = got.channel_scale(c);
  Compare cmp;
  for (std::size_t i = 0; i < m.points.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      const Rgb want = central_difference([&](double dx) {
        TetMesh p = m;
        p.points[i][a] += dx;
        return reference_pixel(p, tf, view, bg);
      }, 1e-4);
      cmp.add(lookup_position(got, static_cast<std::int32_t>(i), a), want, scale,
              label + " position " + std::to_string(i) + "." + "xyz"[a]);
    }
  return cmp;
}

// The pixel Jacobian of each of `rays` through `m`, w.r.t. the vertex scalars or (`positions`) the
// vertex positions, against the differences: the worst over all rays ("ray <index>") within
// kScalarTol or kPositionTol, and shown in a WARN line.
void check_rays(const TetMesh& m, const TransferFunctions& tf, const std::vector<ViewRay>& rays, const Rgb& bg,
                bool positions) {
  const TetTraversal t(m);
  Compare all;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const PixelJacobian j = pixel_jacobian(t, tf, rays[r], bg);
    const std::string label = "ray " + std::to_string(r);
    if (positions) {
      REQUIRE(j.ends_on_edges == 0);
      REQUIRE(!j.position_index.empty());
      all.merge(check_positions(m, tf, rays[r], bg, j, label));
    } else {
      REQUIRE(!j.index.empty());
      all.merge(check_scalars(m, tf, rays[r], bg, j, label));
    }
  }
  WARN("mesh " << (positions ? "position" : "scalar")
               << " Jacobian vs 4th-order differences of the 50-digit render: worst " << all.worst << " at "
               << all.where << " (" << all.entries << " entries, " << rays.size() << " rays)");
  CHECK(all.worst <= (positions ? kPositionTol : kScalarTol));
}

ViewRay toward(const Vec3& from, const Vec3& to) { return {from, (to - from).normalized()}; }

std::vector<ViewRay> generic_rays() {
  return {toward({-2.3, -1.7, -3.1}, {0.31, 0.22, 0.17}), toward({2.9, 0.4, -1.3}, {-0.27, 0.13, 0.41}),
          toward({0.2, 3.3, 0.7}, {-0.11, -0.37, 0.23}), toward({-0.13, 0.21, -0.32}, {2.0, 1.1, 3.0})};
}

}  // namespace

TEST_CASE("mesh gradient: vertex scalars against differences of the 50-digit render", "[grad][mesh]") {
  const TransferFunctions tf = test::kinked_tf();
  const TetMesh m = small_mesh(28);
  const Rgb bg{0.2, 0.1, 0.4};
  std::vector<ViewRay> rays = generic_rays();
  // Through vertices: the box diagonal (corner, the centre vertex, corner; along Kuhn edges) and
  // a ray through a boundary vertex and the centre at an angle.
  rays.push_back(toward({-2, -2, -2}, {1, 1, 1}));
  rays.push_back(toward({-1, 2.5, -1}, m.points[13]));
  rays.push_back(toward({0, -2, 3}, {0, -1, 1}));  // through a boundary edge's vertex
  check_rays(m, tf, rays, bg, false);  // 27 vertices
}

TEST_CASE("mesh gradient: vertex positions against differences of the 50-digit render", "[grad][mesh]") {
  const TransferFunctions tf = test::kinked_tf();
  const TetMesh m = small_mesh(29);
  const Rgb bg{0.2, 0.1, 0.4};
  check_rays(m, tf, generic_rays(), bg, true);  // the last ray starts inside the mesh
}

TEST_CASE("mesh gradient: cell data scalars and positions", "[grad][mesh]") {
  const TransferFunctions tf = test::kinked_tf();
  TetMesh m = small_mesh(30);
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> u(-0.6, 1.0);
  m.cell_scalars.resize(m.tets.size());
  for (double& v : m.cell_scalars) v = u(rng);
  m.scalars.clear();
  const TetTraversal t(m);
  const Rgb bg{0.2, 0.1, 0.4};
  double worst_s = 0.0, worst_p = 0.0;
  for (const ViewRay& ray : generic_rays()) {
    const PixelJacobian j = pixel_jacobian(t, tf, ray, bg);
    REQUIRE(j.cell_scalars);
    worst_s = std::max(worst_s, check_scalars(m, tf, ray, bg, j, "").worst);
    worst_p = std::max(worst_p, check_positions(m, tf, ray, bg, j, "").worst);
  }
  WARN("cell data: scalars worst " << worst_s << ", positions worst " << worst_p);
  CHECK(worst_s <= kScalarTol);
  CHECK(worst_p <= kPositionTol);
}

TEST_CASE("well_conditioned: the decision by squares is the one by norms at and around the threshold",
          "[grad][mesh]") {
  // The reference decision, as mesh/gradients.hpp defines it (three norms, this rounding order),
  // written here again: |det| > kSolveVolumeRatio |a| |b| |c|.
  const auto by_norms = [](double det, const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::isfinite(det) && std::fabs(det) > kSolveVolumeRatio * a.norm() * b.norm() * c.norm();
  };
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-35.0, 35.0);
  long compared = 0, flips = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Columns of scales 1e-35 .. 1e35 (squares outside [1e-60, 1e60] take the norms' form).
    const double sa = std::pow(10.0, e(rng)), sb = std::pow(10.0, e(rng)), sc = std::pow(10.0, e(rng));
    const Vec3 a = sa * Vec3(u(rng), u(rng), u(rng)), b = sb * Vec3(u(rng), u(rng), u(rng)),
               c = sc * Vec3(u(rng), u(rng), u(rng));
    // det stepped ulp by ulp through the norms' threshold R, 3000 ulps each way (the margin,
    // 1e-12, is ~4500 ulps: both sides of the squares' fallback band and the band itself), both signs.
    const double R = kSolveVolumeRatio * a.norm() * b.norm() * c.norm();
    double lo = R, hi = R;
    for (int k = 0; k < 3000; ++k) {
      for (double det : {lo, hi, -lo, -hi}) {
        const bool want = by_norms(det, a, b, c);
        flips += want ? 1 : 0;
        ++compared;
        if (well_conditioned(det, a, b, c) != want) {
          FAIL_CHECK("det " << det << " R " << R << " |a| " << a.norm() << " |b| " << b.norm() << " |c| " << c.norm());
          break;
        }
      }
      lo = std::nextafter(lo, 0.0), hi = std::nextafter(hi, HUGE_VAL);
    }
    // Far from the threshold, and not finite.
    for (double f : {1e-9, 1e-3, 0.5, 2.0, 1e3, 1e9})
      CHECK(well_conditioned(f * R, a, b, c) == by_norms(f * R, a, b, c));
    CHECK_FALSE(well_conditioned(std::nan(""), a, b, c));
    CHECK_FALSE(well_conditioned(HUGE_VAL, a, b, c));
  }
  INFO("compared " << compared << ", well-conditioned " << flips);
  CHECK(flips > compared / 3);  // both decisions were exercised (about half are above R)
  CHECK(flips < 2 * compared / 3);
}

TEST_CASE("RayGradient::all_finite says what a finite channel_scale of every channel says", "[grad][mesh]") {
  // The image loss counts a pixel as failed by all_finite (one pass) where it asked channel_scale
  // per channel: a NaN or an Inf in any block and channel must fail both, finite entries neither.
  RayGradient g;
  g.background = {0.1, -0.2, 0.3};
  g.length.assign(3, Rgb{1.0, -2.0, 3.0});
  g.scalar_far.assign(3, Rgb{-1e300, 2.0, 0.0});
  g.scalar_exit.assign(3, Rgb{4.0, 5.0, -6.0});
  for (int c = 0; c < kChannels; ++c) {
    g.density[c].assign(2, NodeDerivative{0.5, -0.5});
    g.color[c].assign(3, NodeDerivative{1.5, 2.5});
  }
  const auto scales_finite = [](const RayGradient& r) {
    bool ok = true;
    for (int c = 0; c < kChannels; ++c) ok = ok && std::isfinite(r.channel_scale(c));
    return ok;
  };
  CHECK(g.all_finite());
  CHECK(scales_finite(g));
  int cases = 0;
  for (double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL})
    for (int c = 0; c < kChannels; ++c) {
      std::vector<std::function<void(RayGradient&)>> places = {
          [&](RayGradient& r) { r.background[c] = bad; },
          [&](RayGradient& r) { r.length[2][c] = bad; },
          [&](RayGradient& r) { r.scalar_far[0][c] = bad; },
          [&](RayGradient& r) { r.scalar_exit[1][c] = bad; },
          [&](RayGradient& r) { r.density[c][1].position = bad; },
          [&](RayGradient& r) { r.color[c][2].value = bad; }};
      for (const auto& place : places) {
        RayGradient b = g;
        place(b);
        CHECK_FALSE(b.all_finite());
        CHECK_FALSE(scales_finite(b));
        ++cases;
      }
    }
  CHECK(cases == 54);
}

TEST_CASE("mesh gradient: a wrong candidate is caught by the same comparison", "[grad][mesh]") {
  // Two plausible mistakes of a hand-written adjoint: (a) each segment end's dI/ds shared equally
  // among the cell's 4 vertices instead of by barycentric weights; (b) positions moving only the
  // scalar at a fixed crossing (the crossing's motion, hence dI/dL, left out).
  const TransferFunctions tf = test::kinked_tf();
  const TetMesh m = small_mesh(28);
  const TetTraversal t(m);
  const Rgb bg{0.2, 0.1, 0.4};
  const ViewRay ray = generic_rays()[0];
  RayTrace trace;
  t.trace(ray, trace);
  const RayGradient g = exact_ray_gradient(tf, ray_from_trace(trace, bg));
  const PixelJacobian right = pixel_jacobian(t, tf, ray, bg);
  PixelJacobian wrong_s = right, wrong_p = right;
  for (Rgb& d : wrong_s.d_scalar) d = Rgb{};
  for (auto& d : wrong_p.d_position) d = {};
  const std::size_t n = trace.crossings.size();
  for (std::size_t i = 0; i < n; ++i) {
    const CellCrossing& x = trace.crossings[i];
    const std::size_t seg = n - 1 - i;
    for (int end = 0; end < 2; ++end) {
      const Vec3 p = trace.origin + (end ? x.t_out : x.t_in) * trace.direction;
      const auto lambda = barycentric(m, static_cast<std::size_t>(x.cell), p);
      const Vec3& grad_s = t.gradient(static_cast<std::size_t>(x.cell));
      for (std::size_t k = 0; k < 4; ++k) {
        const std::int32_t v = m.tets[static_cast<std::size_t>(x.cell)][k];
        const auto si = static_cast<std::size_t>(std::lower_bound(right.index.begin(), right.index.end(), v) - right.index.begin());
        const auto pi = static_cast<std::size_t>(std::lower_bound(right.position_index.begin(), right.position_index.end(), v) - right.position_index.begin());
        for (int c = 0; c < kChannels; ++c) {
          const double gs = end ? g.scalar_far[seg][c] : g.scalar_exit[seg][c];
          wrong_s.d_scalar[si][c] += gs / 4.0;
          if (pi < wrong_p.position_index.size() && wrong_p.position_index[pi] == v)
            for (int a = 0; a < 3; ++a) wrong_p.d_position[pi][static_cast<std::size_t>(a)][c] -= gs * lambda[k] * grad_s[a];
        }
      }
    }
  }
  const double right_err = check_scalars(m, tf, ray, bg, right, "").worst;
  const double wrong_s_err = check_scalars(m, tf, ray, bg, wrong_s, "").worst;
  const double wrong_p_err = check_positions(m, tf, ray, bg, wrong_p, "").worst;
  WARN("right " << right_err << ", equal shares " << wrong_s_err << ", positions without the crossing's motion "
       << wrong_p_err);
  CHECK(right_err <= kScalarTol);
  CHECK(wrong_s_err > 1e-2);
  CHECK(wrong_p_err > 1e-2);
}

TEST_CASE("mesh gradient: image loss against differences of the 50-digit loss", "[grad][mesh]") {
  MeshCase mc;
  mc.source = "test";
  mc.transfer = test::kinked_tf();
  mc.mesh = small_mesh(31);
  mc.background = {0.2, 0.1, 0.4};
  Camera cam;
  cam.position = Vec3(0.37, -0.21, 4.0);
  cam.look_at = Vec3(0.03, 0.05, 0.0);
  cam.width = 6;
  cam.height = 5;
  cam.fov_deg = 35.0;
  mc.camera = cam;
  const TetTraversal t(mc.mesh);
  Image target(cam.width, cam.height, Rgb{0.3, 0.5, 0.2});
  target.at(2, 2) = Rgb{0.9, 0.1, 0.0};
  const LossGradient lg = image_loss_gradient(mc, t, target, 2);
  REQUIRE(lg.pixels_failed == 0);
  REQUIRE(lg.d_scalar.size() == mc.mesh.points.size());
  const auto loss_of = [&](const TetMesh& m) {
    double loss = 0.0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Rgb i = reference_pixel(m, mc.transfer, cam.ray_for_pixel(x, y), mc.background);
        for (int c = 0; c < kChannels; ++c) loss += (i[c] - target.at(x, y)[c]) * (i[c] - target.at(x, y)[c]);
      }
    return loss;
  };
  CHECK(std::fabs(lg.loss - loss_of(mc.mesh)) <= 1e-13 * lg.loss);
  double scale = 0.0;
  for (double d : lg.d_scalar) scale = std::max(scale, std::fabs(d));
  for (const auto& d : lg.d_position) for (double e : d) scale = std::max(scale, std::fabs(e));
  const auto diff = [&](const std::function<void(TetMesh&, double)>& move) {
    const double h = 1e-4;
    std::array<double, 4> f{};
    const double steps[4] = {-2 * h, -h, h, 2 * h};
    for (int k = 0; k < 4; ++k) {
      TetMesh m = mc.mesh;
      move(m, steps[k]);
      f[static_cast<std::size_t>(k)] = loss_of(m);
    }
    return (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h);
  };
  double worst = 0.0;
  for (std::size_t i : {4u, 13u, 22u}) {  // interior and face vertices the camera sees
    REQUIRE(std::fabs(lg.d_scalar[i]) > 1e-3 * scale);  // a vertex the loss depends on
    worst = std::max(worst, std::fabs(lg.d_scalar[i] - diff([i](TetMesh& m, double d) { m.scalars[i] += d; })) / scale);
    for (std::size_t a = 0; a < 3; ++a)
      worst = std::max(worst, std::fabs(lg.d_position[i][a] -
                                        diff([i, a](TetMesh& m, double d) { m.points[i][static_cast<Eigen::Index>(a)] += d; })) / scale);
  }
  WARN("image loss gradient (6 x 5 pixels, 3 vertices, scalars and positions) vs differences of the 50-digit loss: worst " << worst
       << ", pixels with an end on an edge: " << lg.ends_on_edges);
  CHECK(lg.ends_on_edges == 0);
  CHECK(worst <= kPositionTol);
  // Without positions: the same scalar gradient (summation order aside), no position array.
  const LossGradient scalars_only = image_loss_gradient(mc, t, target, 2, false);
  REQUIRE(scalars_only.d_scalar.size() == lg.d_scalar.size());
  CHECK(scalars_only.d_position.empty());
  for (std::size_t i = 0; i < lg.d_scalar.size(); ++i)
    CHECK(std::fabs(scalars_only.d_scalar[i] - lg.d_scalar[i]) <= 1e-14 * scale);
  // Rows go to fixed workers (parallel_for_striped): a second run on 2 threads, the same bits.
  const LossGradient again = image_loss_gradient(mc, t, target, 2);
  CHECK(again.loss == lg.loss);
  CHECK(again.d_scalar == lg.d_scalar);
  CHECK(again.d_position == lg.d_position);
}

namespace {

// Per-channel transfer functions on the mesh's scalar range [-0.6, 1] with jumps: density r jumps
// 0.4 -> 2.2 between linear pieces at 0.1, density b is a pure step 0.3 -> 1.6 at 0.35, colour g
// jumps 0.2 -> 0.9 at 0.45; the rest linear with a kink.
TransferFunctions jump_tf() {
  TransferFunctions tf = test::kinked_tf();
  tf.density[0] = {{-0.4, 0.1, 0.1, 0.8}, {0.5, 0.4, 2.2, 1.5}};
  tf.density[2] = {{0.35, 0.35}, {0.3, 1.6}};
  tf.color[1] = {{-0.4, 0.45, 0.45, 0.8}, {0.3, 0.2, 0.9, 0.6}};
  return tf;
}

// The jumps the ray's segments cross (strictly inside a segment), and the smallest distance of a
// segment end's scalar to a jump (the differences move an end's scalar by up to a few steps).
struct JumpCrossings {
  int crossed = 0;
  double nearest_end = HUGE_VAL;
};
JumpCrossings jump_crossings(const Ray& ray, const std::vector<double>& jumps) {
  JumpCrossings out;
  for (const Segment& seg : ray.segments)
    for (const double x : jumps) {
      out.crossed += (seg.scalar_far - x) * (seg.scalar_exit - x) < 0.0;
      out.nearest_end = std::min({out.nearest_end, std::fabs(seg.scalar_far - x), std::fabs(seg.scalar_exit - x)});
    }
  return out;
}

}  // namespace

TEST_CASE("mesh gradient across transfer-function jumps: scalars and positions against the 50-digit render",
          "[grad][mesh][grad_jump]") {
  const TransferFunctions tf = jump_tf();
  const std::vector<double> jumps = {0.1, 0.35, 0.45};
  const TetMesh m = small_mesh(28);
  const TetTraversal t(m);
  const Rgb bg{0.2, 0.1, 0.4};
  Compare scalars, positions;
  int crossed = 0;
  for (const ViewRay& view : generic_rays()) {
    const JumpCrossings jc = jump_crossings(mesh_ray(t, view, bg), jumps);
    crossed += jc.crossed;
    // The differences (steps 1e-4, up to 2e-4 each way) must not move a segment end across a
    // jump (where the one-sided derivatives differ): every end stays > 5e-3 away.
    INFO("nearest segment end to a jump " << jc.nearest_end);
    REQUIRE(jc.nearest_end > 5e-3);
    const PixelJacobian j = pixel_jacobian(t, tf, view, bg);
    CHECK(j.undefined.empty());
    REQUIRE(j.ends_on_edges == 0);
    const Compare s = check_scalars(m, tf, view, bg, j, "scalars");
    const Compare p = check_positions(m, tf, view, bg, j, "positions");
    if (!(s.worst <= scalars.worst)) { scalars.worst = s.worst; scalars.where = s.where; }
    if (!(p.worst <= positions.worst)) { positions.worst = p.worst; positions.where = p.where; }
    scalars.entries += s.entries;
    positions.entries += p.entries;
  }
  WARN("mesh Jacobian across jumps vs 4th-order differences of the 50-digit render: scalars worst "
       << scalars.worst << " at " << scalars.where << " (" << scalars.entries << " entries), positions worst "
       << positions.worst << " at " << positions.where << " (" << positions.entries << " entries); " << crossed
       << " jump crossings on 4 rays");
  // Not vacuous: the rays cross the jumps (each crossing adds its term to the segment's dI/ds).
  CHECK(crossed >= 4);
  CHECK(scalars.worst <= kScalarTol);
  CHECK(positions.worst <= kPositionTol);
}
