// Cells (Eq. 9, Eq. 13), traversal (vertices, edges, faces, non-convex, gaps, eye inside),
// the linear-field target, gradients, shading, rays that miss, and rendering (tag [mesh]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include "rayint/studies/mesh_agreement.hpp"
#include "mesh_case_fixtures.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/gradients.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/surface_shading.hpp"
#include "rayint/mesh/tet_cell.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/render/mesh_render.hpp"
#include "test_paths.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::concat;

namespace {

double box_chord(const Vec3& lo, const Vec3& hi, const Vec3& o, Vec3 d) {
  d.normalize();
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return 0.0;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return std::max(0.0, t1 - t0);
}

double inside_length(const TetTraversal& m, const ViewRay& r, TraversalStats* stats = nullptr) {
  double len = 0.0;
  for (const Segment& s : mesh_ray(m, r, Rgb{0, 0, 0}, stats).segments) len += s.length;
  return len;
}

}  // namespace

TEST_CASE("Eq. 9 on known tetrahedra", "[mesh]") {
  SECTION("unit right tet, s = 1 + 2x + 3y + 4z: c = (1, 2, 3, 4)") {
    const LinearTetField f = fit_linear_tet({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, {1, 3, 4, 5});
    CHECK(f.c1() == 1.0);
    CHECK(f.gradient == Vec3(2, 3, 4));
  }
  SECTION("a sliver (height 1e-3 against edges 1): c recovered") {
    const std::array<Vec3, 4> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 1e-3)};
    const auto s = [](const Vec3& p) { return -7.0 + 0.25 * p.x() + 0.5 * p.y() - 2.0 * p.z(); };
    const LinearTetField f = fit_linear_tet(x, {s(x[0]), s(x[1]), s(x[2]), s(x[3])});
    CHECK(f.c1() == -7.0);  // x0 = 0: c1 = s0
    CHECK((f.gradient - Vec3(0.25, 0.5, -2.0)).norm() <= 1e-12);  // rounding of s / height 1e-3
    for (const Vec3& p : x) CHECK(std::fabs(f.at(p) - s(p)) <= 1e-14 * 7.0);
  }
  SECTION("far from the origin (|x0| = 2.3e3): the centred form reproduces the vertex scalars") {
    const Vec3 shift(1e3, -2e3, 5e2);
    const std::array<Vec3, 4> x{shift + Vec3(0, 0, 0), shift + Vec3(1, 0, 0), shift + Vec3(0, 1, 0), shift + Vec3(0, 0, 1)};
    const std::array<double, 4> s{0.1, 0.7, -0.3, 0.45};
    const LinearTetField f = fit_linear_tet(x, s);
    for (std::size_t k = 0; k < 4; ++k) CHECK(std::fabs(f.at(x[k]) - s[k]) <= 1e-14);
  }
  SECTION("Eq. 13: v at the entry point, w = gradient . direction") {
    const LinearTetField f = fit_linear_tet({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, {1, 3, 4, 5});
    const Eq13 e = ray_parameters(f, Vec3(0.1, 0.2, 0.3), Vec3(0, 0.6, 0.8));
    CHECK(e.v == Approx(1 + 0.2 + 0.6 + 1.2).epsilon(1e-15));
    CHECK(e.w == Approx(3 * 0.6 + 4 * 0.8).epsilon(1e-15));
  }
}

namespace {

// Eq. 9's gradient against its 50-digit value (tet_cell.hpp states the bounds these measure).
// The reference solves the same system, edges and scalar differences of the same doubles, by
// Cramer's rule in cpp_bin_float_50 (~1e-50 relative; the worst condition number sampled is
// ~1e13). Errors are |g - g*| / |g*| and that over eps kappa_F, kappa_F = |A|_F |A^-1|_F of the
// edge matrix A (the scale of any backward-stable solve's error); Eigen's LU with full pivoting,
// the method before issue 33, beside the closed form.
struct Eq9Accuracy {
  long tets = 0;
  double closed = 0.0, lu = 0.0;                        // max relative error
  double closed_over_kappa = 0.0, lu_over_kappa = 0.0;  // max of the error / (eps kappa_F)
  double worst_kappa = 0.0;
  long constant = 0, constant_exact = 0;  // cells with equal vertex scalars, those given 0 exactly
  void add(const std::array<Vec3, 4>& x, const std::array<double, 4>& s) {
    using Real = boost::multiprecision::cpp_bin_float_50;
    std::array<std::array<Real, 3>, 3> e;
    std::array<Real, 3> d;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) e[k][j] = Real(x[k + 1][j]) - Real(x[0][j]);
      d[k] = Real(s[k + 1]) - Real(s[0]);
    }
    const auto cross = [](const std::array<Real, 3>& u, const std::array<Real, 3>& v) {
      return std::array<Real, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    };
    const auto c23 = cross(e[1], e[2]), c31 = cross(e[2], e[0]), c12 = cross(e[0], e[1]);
    const Real det = e[0][0] * c23[0] + e[0][1] * c23[1] + e[0][2] * c23[2];
    std::array<Real, 3> g;
    Real a2 = 0, inv2 = 0, g2 = 0;
    for (int j = 0; j < 3; ++j) {
      g[j] = (d[0] * c23[j] + d[1] * c31[j] + d[2] * c12[j]) / det;
      g2 += g[j] * g[j];
      inv2 += c23[j] * c23[j] + c31[j] * c31[j] + c12[j] * c12[j];
      for (int k = 0; k < 3; ++k) a2 += e[k][j] * e[k][j];
    }
    if (g2 == 0) {  // a constant field: the closed form gives 0 exactly
      constant_exact += fit_linear_tet(x, s).gradient == Vec3::Zero();
      ++constant;
      return;
    }
    const double kappa = static_cast<double>(sqrt(a2 * inv2) / abs(det));
    const auto error = [&](const Vec3& got) {
      Real r2 = 0;
      for (int j = 0; j < 3; ++j) r2 += (Real(got[j]) - g[j]) * (Real(got[j]) - g[j]);
      return static_cast<double>(sqrt(r2 / g2));
    };
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.row(k) = (x[static_cast<std::size_t>(k + 1)] - x[0]).transpose();
    const double closed_error = error(fit_linear_tet(x, s).gradient);
    const double lu_error = error(edges.fullPivLu().solve(Eigen::Vector3d(s[1] - s[0], s[2] - s[0], s[3] - s[0])));
    const double eps = std::numeric_limits<double>::epsilon();
    closed = std::max(closed, closed_error);
    lu = std::max(lu, lu_error);
    closed_over_kappa = std::max(closed_over_kappa, closed_error / (eps * kappa));
    lu_over_kappa = std::max(lu_over_kappa, lu_error / (eps * kappa));
    worst_kappa = std::max(worst_kappa, kappa);
    ++tets;
  }
  void add(const TetMesh& m) {
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
      std::array<Vec3, 4> x;
      std::array<double, 4> s{};
      for (std::size_t k = 0; k < 4; ++k) {
        const auto p = static_cast<std::size_t>(m.tets[t][k]);
        x[k] = m.points[p];
        s[k] = m.cell_scalars.empty() ? m.scalars[p] : m.cell_scalars[t];
      }
      add(x, s);
    }
  }
  std::string summary() const {
    std::ostringstream o;
    o << tets << " tets (and " << constant << " of a constant field, " << constant_exact << " given 0 exactly): max relative error closed form " << closed << ", LU " << lu << "; over eps kappa_F: closed "
      << closed_over_kappa << ", LU " << lu_over_kappa << "; worst kappa_F " << worst_kappa;
    return o.str();
  }
};

// The worst shapes the mesh checks accept (tet_mesh.hpp: |6 V| > kDegenerateTetRatio l^3, l the
// longest edge): slivers (four points nearly in a plane) and needles and caps (three nearly on a
// line), |6 V| / l^3 from ~1e-12 to 1e-2, turned at random, up to 1e3 sizes from the origin,
// scalars at random in [-1, 1] (the field's gradient across the flat direction ~ 1 / height).
void add_worst_shapes(Eq9Accuracy& acc, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), decade(-11.5, -2.0);
  const auto random_unit = [&] {
    Vec3 v;
    do v = Vec3(unit(rng), unit(rng), unit(rng));
    while (v.norm() < 0.1 || v.norm() > 1.0);
    return Vec3(v / v.norm());
  };
  for (int i = 0; i < count; ++i) {
    const double ratio = std::pow(10.0, decade(rng));
    const Vec3 n = random_unit();
    Vec3 u = random_unit().cross(n);
    u /= u.norm();
    const Vec3 v = n.cross(u);
    const Vec3 origin = std::pow(10.0, 3.0 * (unit(rng) + 1.0) / 2.0) * random_unit();
    std::array<Vec3, 4> x;
    if (i % 2 == 0) {  // sliver: a quadrilateral in the (u, v) plane, point 3 lifted by h along n
      x = {origin, origin + u, origin + (0.9 + 0.2 * unit(rng)) * (u + v), origin + v};
      x[3] += ratio * n;  // |6 V| = |(u) . ((u+v) x (v + h n))| ~ h, l ~ sqrt(2): ratio ~ 1e-12 .. 1e-2
    } else {  // needle or cap: points 0..2 nearly on the line along u, point 3 off it
      x = {origin, origin + u, origin + (0.5 + 0.4 * unit(rng)) * u + ratio * v, origin + 0.5 * u + n};
    }
    const std::array<double, 4> s{unit(rng), unit(rng), unit(rng), unit(rng)};
    // Only shapes the checks accept (classify_tet's test, the same doubles).
    TetMesh one;
    one.points = {x[0], x[1], x[2], x[3]};
    one.tets = {{0, 1, 2, 3}};
    const TetShape shape = classify_tet(one, 0);
    if (shape != TetShape::Positive && shape != TetShape::Inverted) continue;
    acc.add(x, s);
  }
}

}  // namespace

TEST_CASE("Eq. 9: the closed-form gradient against 50 digits, with Eigen's LU beside it", "[mesh]") {
  // The figures quoted in tet_cell.hpp come from this test (run with -s to print them).
  SECTION("the 105k-tet ball of the scaling runs (rayint generate-mesh ball --n 13)") {
    Eq9Accuracy acc;
    acc.add(generate_mesh("ball", 13, 1).mesh);
    INFO(acc.summary());
    CHECK(acc.tets + acc.constant == 105456);
    CHECK(acc.constant_exact == acc.constant);
    CHECK(acc.closed <= 1e-13);
    CHECK(acc.closed_over_kappa <= 1.0);
    WARN(acc.summary());
  }
  SECTION("every fixture mesh the tetrahedral reader takes") {
    Eq9Accuracy acc;
    int meshes = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(RAYINT_SOURCE_DIR + "/tests/fixtures")) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".vtk" && ext != ".vtu" && ext != ".msh" && ext != ".ele" && ext != ".pvtu") continue;
      TetMesh m;
      try {
        m = read_mesh_file(entry.path().string());
      } catch (const std::exception&) {
        continue;  // other cells, no scalar, or a file meant to be refused
      }
      acc.add(m);
      ++meshes;
    }
    INFO(meshes << " meshes, " << acc.summary());
    CHECK(meshes >= 20);
    CHECK(acc.closed <= 1e-13);
    CHECK(acc.closed_over_kappa <= 1.0);
    WARN(meshes << " meshes, " << acc.summary());
  }
  SECTION("the worst shapes the mesh checks accept") {
    Eq9Accuracy acc;
    add_worst_shapes(acc, 100000, 33);
    INFO(acc.summary());
    CHECK(acc.tets > 90000);
    CHECK(acc.worst_kappa > 1e11);
    CHECK(acc.closed_over_kappa <= 1.0);
    WARN(acc.summary());
  }
}

TEST_CASE("Traversal: rays exactly through vertices, along edges and in faces give the analytic chord", "[mesh]") {
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  TetMesh m = structured_box_mesh(lo, hi, 4, 4, 4);
  assign_field(m, [](const Vec3& p) { return p.x() + 2 * p.y() - p.z(); });
  const TetTraversal mesh(m, "box");
  struct R {
    Vec3 o, d;
    const char* what;
  };
  const R rays[] = {
      {Vec3(-1, 0.25, 0.5), Vec3(1, 0, 0), "along grid edges through vertices"},
      {Vec3(-1, -1, -1), Vec3(1, 1, 1), "the main diagonal: Kuhn diagonal edges and vertices"},
      {Vec3(2, 2, 2), Vec3(-1, -1, -1), "the main diagonal, reversed"},
      {Vec3(-1, -1, 0.5), Vec3(1, 1, 0), "face diagonals through vertices"},
      {Vec3(0.5, 0.5, 3), Vec3(0, 0, -1), "along interior edges"},
      {Vec3(-1, 0.25, 0.1), Vec3(1, 0, 0.3), "inside the grid plane y = 0.25 (through faces)"},
      {Vec3(-1, 0.3, 0.25), Vec3(1, 0.1, 0), "inside the grid plane z = 0.25"},
      {Vec3(0.5, 0.5, 0.5), Vec3(1, 0.2, 0.1), "from a vertex inside the mesh (eye inside)"},
      {Vec3(0.3, 0.6, 0.2), Vec3(-0.3, 0.1, 1), "from inside a cell"},
  };
  TraversalStats stats;
  for (const R& r : rays) {
    INFO(r.what);
    const double chord = box_chord(lo, hi, r.o, r.d);
    const double len = inside_length(mesh, ViewRay{r.o, r.d.normalized()}, &stats);
    CHECK(std::fabs(len - chord) <= 1e-14 * chord);
  }
  SECTION("random rays through pairs of grid vertices (rayint mesh-agreement --vertex-rays)") {
    const VertexRayChords v = measure_vertex_ray_chords(4, 400, 11);  // 384 tets, seed 11
    INFO("rays " << v.rays << ", max length error " << v.max_length_abs);
    CHECK(v.rays > 200);
    CHECK(v.max_length_abs <= 1e-14);  // cube edge 1; measured 3.1e-15 over 48,938 rays on 24,576 tets
    CHECK(v.zero_length_steps > 0);
    CHECK(v.budget_exhausted == 0);
  }
  CHECK(stats.budget_exhausted == 0);
  CHECK(stats.zero_length_steps > 0);  // the rays above do pass through edges and vertices
}

TEST_CASE("Traversal: scalars at crossings follow Eq. 13 of each cell", "[mesh]") {
  TetMesh m = generate_mesh("linear-box", 2, 3).mesh;
  const auto s = [](const Vec3& p) { return 0.5 + 0.3 * p.x() - 0.2 * p.y() + 0.4 * p.z(); };
  const TetTraversal mesh(m, "box");
  RayTrace tr;
  mesh.trace(ViewRay{Vec3(-3, 0.2, 0.1), Vec3(1, 0.1, -0.05).normalized()}, tr);
  REQUIRE(tr.crossings.size() > 5);
  for (std::size_t i = 0; i < tr.crossings.size(); ++i) {
    const CellCrossing& c = tr.crossings[i];
    CHECK(std::fabs(c.s_in - s(tr.origin + c.t_in * tr.direction)) < 1e-14);
    CHECK(std::fabs(c.s_out - s(tr.origin + c.t_out * tr.direction)) < 1e-14);
    if (i > 0) CHECK(c.t_in == tr.crossings[i - 1].t_out);  // contiguous inside a convex mesh
  }
}

TEST_CASE("Traversal: a non-convex mesh (the ray leaves and re-enters) and a mesh with a gap", "[mesh]") {
  SECTION("square ring: through the hole, and through the hole's corner edges") {
    const TetTraversal ring(generate_mesh("ring", 1, 1).mesh, "ring");
    CHECK(std::fabs(inside_length(ring, ViewRay{Vec3(-5, 0, 0.1), Vec3(1, 0, 0)}) - 1.2) < 1e-14);
    CHECK(std::fabs(inside_length(ring, ViewRay{Vec3(-5, 0.7, 0.1), Vec3(1, 0, 0)}) - 2.0) < 1e-14);
    const double diag = 1.2 * std::sqrt(2.0);
    CHECK(std::fabs(inside_length(ring, ViewRay{Vec3(-2, -2, 0.1), Vec3(1, 1, 0).normalized()}) - diag) < 1e-14);
    RayTrace tr;
    ring.trace(ViewRay{Vec3(-5, 0, 0.1), Vec3(1, 0, 0)}, tr);
    int gaps = 0;
    for (std::size_t i = 1; i < tr.crossings.size(); ++i)
      if (tr.crossings[i].t_in - tr.crossings[i - 1].t_out > 0.79) ++gaps;
    CHECK(gaps == 1);
  }
  SECTION("two boxes with a gap between them") {
    TetMesh a = structured_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 3, 3, 3);
    const TetMesh b = structured_box_mesh(Vec3(2, 0, 0), Vec3(3, 1, 1), 2, 2, 2);
    const TetTraversal two(concat(a, b), "two");
    CHECK(std::fabs(inside_length(two, ViewRay{Vec3(-1, 0.3, 0.6), Vec3(1, 0, 0)}) - 2.0) < 1e-14);
    CHECK(std::fabs(inside_length(two, ViewRay{Vec3(4, 0.5, 0.5), Vec3(-1, 0, 0)}) - 2.0) < 1e-14);
    CHECK(inside_length(two, ViewRay{Vec3(1.5, 0.5, 5), Vec3(0, 0, -1)}) == 0.0);  // into the gap
  }
}

TEST_CASE("Linear field over the whole mesh: mesh path == one exact segment to 1e-13 (2000 random rays)", "[mesh]") {
  MeshAgreementOptions o;  // 2000 rays, seed 2026, linear-box n = 3 (1,296 tets)
  const MeshAgreement a = measure_linear_field_agreement(o);
  INFO("hits " << a.hits << ", max rel " << a.max_rel << ", max length error " << a.max_length_abs);
  CHECK(a.hits > 1000);
  CHECK(a.segments > 10 * a.hits);
  CHECK(a.max_rel <= test::Tolerances::exact_rel);
  // Geometry: measured 1.3e-14 over 100,000 rays (seed 2026) on a box of edge 2, from grazing rays
  // (an end point moved by ~1 ulp across the ray moves along it by 1 ulp / sin(angle)).
  CHECK(a.max_length_abs <= 5e-14);
  CHECK(a.budget_exhausted == 0);
}

TEST_CASE("A ray that misses the mesh: every method and the reference return the background", "[mesh]") {
  // One shared density and a constant colour, so that every method (the particle model too) applies.
  TransferFunctions tf;
  const PiecewiseLinear density{{0.0, 1.0}, {0.5, 2.0}}, color{{0.0}, {0.7}};
  tf.density = {density, density, density};
  tf.color = {color, color, color};
  Ray miss;
  miss.background = {0.3, 0.2, 0.1};
  for (const std::string& name : method_names()) {
    INFO(name);
    const auto m = make_integrator(parse_method_spec(name), tf);
    const RayResult r = m->integrate(miss, nullptr);
    for (int ch = 0; ch < kChannels; ++ch) {
      CHECK(r.intensity[ch] == miss.background[ch]);
      CHECK(r.transmittance[ch] == 1.0);
    }
  }
  const ReferenceRay ref = reference_ray(tf, miss);
  for (int ch = 0; ch < kChannels; ++ch) CHECK(ref.intensity[ch].hi == miss.background[ch]);
}

TEST_CASE("Gradients (Sec. 3.2): cell, vertex average and inverse distance on a linear field", "[mesh]") {
  const TetTraversal mesh(generate_mesh("linear-box", 2, 5).mesh, "box");
  const Vec3 g(0.3, -0.2, 0.4);
  for (GradientMode mode : {GradientMode::cell, GradientMode::vertex_average, GradientMode::inverse_distance}) {
    INFO(gradient_mode_name(mode));
    const GradientField f(mesh, mode);
    for (std::size_t c = 0; c < mesh.cell_count(); c += 37) {
      Vec3 centroid = Vec3::Zero();
      for (auto i : mesh.mesh().tets[c]) centroid += mesh.mesh().points[i] / 4.0;
      CHECK((f.at(c, centroid) - g).norm() <= 1e-12);
    }
  }
  SECTION("on a radial field the smooth gradients are continuous across faces, the cell one is not") {
    const TetTraversal ball(generate_mesh("ball", 2, 1).mesh, "ball");
    const GradientField cell(ball, GradientMode::cell), avg(ball, GradientMode::vertex_average);
    double jump_cell = 0.0, jump_avg = 0.0;
    for (std::size_t c = 0; c < ball.cell_count(); ++c)
      for (int k = 0; k < 4; ++k) {
        const std::int32_t nb = ball.neighbor(c, k);
        if (nb < 0) continue;
        Vec3 p = Vec3::Zero();  // the shared face's centroid
        for (int j = 0; j < 4; ++j)
          if (j != k) p += ball.mesh().points[ball.mesh().tets[c][static_cast<std::size_t>(j)]] / 3.0;
        jump_cell = std::max(jump_cell, (cell.at(c, p) - cell.at(static_cast<std::size_t>(nb), p)).norm());
        jump_avg = std::max(jump_avg, (avg.at(c, p) - avg.at(static_cast<std::size_t>(nb), p)).norm());
      }
    CHECK(jump_cell > 0.1);
    CHECK(jump_avg < 1e-12);
  }
}

TEST_CASE("Face adjacency: neighbours and boundary faces match a map of the tets' faces", "[mesh]") {
  // Independent reference: every face as a sorted point triple, mapped to the tets that hold it.
  const TetTraversal ball(generate_mesh("ball", 3, 1).mesh, "ball");
  const TetMesh& m = ball.mesh();
  std::map<std::array<std::int32_t, 3>, std::vector<std::int32_t>> holders;
  auto face_of = [&](std::size_t c, int k) {
    std::array<std::int32_t, 3> f{};
    std::size_t i = 0;
    for (int j = 0; j < 4; ++j)
      if (j != k) f[i++] = m.tets[c][static_cast<std::size_t>(j)];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (std::size_t c = 0; c < m.tets.size(); ++c)
    for (int k = 0; k < 4; ++k) holders[face_of(c, k)].push_back(static_cast<std::int32_t>(c));
  std::size_t boundary = 0;
  for (const auto& [f, cells] : holders) boundary += cells.size() == 1;
  CHECK(ball.face_count() == holders.size());
  CHECK(ball.boundary_face_count() == boundary);
  CHECK(boundary > 0);
  long mismatches = 0;
  for (std::size_t c = 0; c < m.tets.size(); ++c)
    for (int k = 0; k < 4; ++k) {
      const std::vector<std::int32_t>& cells = holders[face_of(c, k)];
      const std::int32_t expected = cells.size() == 1 ? -1 : (cells[0] == static_cast<std::int32_t>(c) ? cells[1] : cells[0]);
      mismatches += ball.neighbor(c, k) != expected;
    }
  CHECK(mismatches == 0);
  for (std::size_t i = 0; i < ball.boundary_face_count(); ++i) {
    const TetTraversal::Face& f = ball.boundary_face(i);
    const auto it = holders.find(f.points);
    REQUIRE(it != holders.end());
    CHECK(it->second.size() == 1);
    CHECK(f.cells[0] == it->second[0]);
    CHECK(f.cells[1] == -1);
  }
}

TEST_CASE("Isosurface shading of flagged intervals", "[mesh]") {
  const TetTraversal mesh(generate_mesh("linear-box", 2, 5).mesh, "box");
  const TransferFunctions tf = agreement_transfer_functions();
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  const GradientField grad(mesh, GradientMode::cell);
  RayTrace tr;
  const Vec3 d = Vec3(0.1, -0.2, -1).normalized();
  mesh.trace(ViewRay{Vec3(0.1, 0.2, 4), d}, tr);
  const Ray ray = ray_from_trace(tr, Rgb{0, 0, 0});
  const RayResult plain = exact->integrate(ray, nullptr);
  SurfaceShading sh;
  sh.enabled = true;
  sh.surfaces = {{-10.0, 10.0}};  // everything flagged
  SECTION("ambient 1, diffuse 0: the unshaded integral") {
    sh.ambient = 1.0;
    sh.diffuse = 0.0;
    const RayResult r = integrate_shaded(*exact, tr, Rgb{0, 0, 0}, sh, grad);
    for (int ch = 0; ch < kChannels; ++ch) CHECK(r.intensity[ch] == Approx(plain.intensity[ch]).epsilon(1e-13));
  }
  SECTION("headlight, diffuse only: emission scaled by |g.d|/|g|") {
    sh.ambient = 0.0;
    sh.diffuse = 1.0;
    const Vec3 g(0.3, -0.2, 0.4);
    const double factor = std::fabs(g.dot(d)) / g.norm();
    const RayResult r = integrate_shaded(*exact, tr, Rgb{0, 0, 0}, sh, grad);
    for (int ch = 0; ch < kChannels; ++ch) CHECK(r.intensity[ch] == Approx(factor * plain.intensity[ch]).epsilon(1e-12));
  }
  SECTION("a narrow flagged interval changes only part of the ray") {
    sh.surfaces = {{0.45, 0.55}};
    sh.ambient = 0.0;
    sh.diffuse = 0.0;
    const RayResult r = integrate_shaded(*exact, tr, Rgb{0, 0, 0}, sh, grad);
    CHECK(r.intensity[0] < plain.intensity[0]);
    CHECK(r.intensity[0] > 0.0);
  }
}

TEST_CASE("Rendering a mesh case: the exact method's piece count is the render's own", "[mesh]") {
  // The exact method's grey batch counts the pieces while splitting (integrate_many's `pieces`);
  // riemann does not split, so the render counts them itself: the two statistics must agree.
  MeshCase mc = rayint::test::ball_render_case(12);
  mc.transfer.density[1] = mc.transfer.density[2] = mc.transfer.density[0];
  REQUIRE(mc.transfer.grey());
  const TetTraversal mesh(mc.mesh, "ball");
  const auto exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  const auto riemann = make_integrator(parse_method_spec("riemann:n=4"), mc.transfer);
  MeshRenderSettings one;
  one.threads = 1;
  const MeshRender a = render_mesh(mc, mesh, *exact, nullptr, one);
  const MeshRender b = render_mesh(mc, mesh, *riemann, nullptr, one);
  CHECK(a.cost.segments == b.cost.segments);
  CHECK(a.cost.segments > 100);
  CHECK(a.cost.pieces == b.cost.pieces);
  CHECK(a.cost.pieces > a.cost.segments);  // this transfer function has breakpoints inside the ball's range
}

TEST_CASE("Rendering a mesh case: threads do not change the image, comparison and progress", "[mesh]") {
  const rayint::test::BallRender ball(16);
  MeshRenderSettings one;
  one.threads = 1;
  int last_done = -1, last_total = -1;
  MeshRenderSettings two;
  two.threads = 2;
  two.progress = [&](int done, int total) {
    last_done = done;
    last_total = total;
  };
  const MeshRender a = render_mesh(ball.mc, ball.mesh, *ball.exact, ball.exact.get(), one);
  const MeshRender b = render_mesh(ball.mc, ball.mesh, *ball.exact, ball.riemann.get(), two);
  CHECK(a.image.pixels == b.image.pixels);
  CHECK(last_done == 16);
  CHECK(last_total == 16);
  CHECK(a.error.max_rel == 0.0);
  CHECK(b.error.max_rel > 1e-6);
  CHECK(a.cost.rays == 320);
  CHECK(a.cost.pieces >= a.cost.segments);
  // Each pixel equals the Ray path used by `rayint eval`.
  const Ray r = mesh_ray(ball.mesh, ball.mc.camera->ray_for_pixel(7, 9), ball.mc.background);
  CHECK(ball.exact->integrate(r, nullptr).intensity == a.image.at(7, 9));
  CHECK(a.image.at(0, 0) == ball.mc.background);  // a corner pixel misses the ball
}
