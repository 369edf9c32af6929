// Meshes as they come (issue 14): inverted tets reoriented, zero-volume and sliver tets dropped,
// counted; traversal across a dropped degenerate tet; the Kuhn split; --strict-mesh refusals
// (tag [mesh][repair]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "rayint/input/case_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "tolerances.hpp"
#include "mesh_case_fixtures.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

namespace {

// Rays from random points on a sphere of radius 4 toward random points in [-1.2, 1.2]^3.
std::vector<ViewRay> random_rays(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  std::vector<ViewRay> rays;
  for (int i = 0; i < n; ++i) {
    Vec3 o(g(rng), g(rng), g(rng));
    o = 4.0 * o.normalized();
    const Vec3 target(u(rng), u(rng), u(rng));
    rays.push_back(ViewRay{o, target - o});
  }
  return rays;
}

double max_abs_difference(const TetTraversal& a, const TetTraversal& b, const std::vector<ViewRay>& rays,
                          const RayIntegrator& exact, long* segments) {
  double worst = 0.0;
  for (const ViewRay& r : rays) {
    const Ray ra = mesh_ray(a, r, {0.1, 0.2, 0.3}), rb = mesh_ray(b, r, {0.1, 0.2, 0.3});
    *segments += static_cast<long>(ra.segments.size());
    const RayResult ia = exact.integrate(ra, nullptr), ib = exact.integrate(rb, nullptr);
    for (int c = 0; c < kChannels; ++c) worst = std::max(worst, std::fabs(ia.intensity[c] - ib.intensity[c]));
  }
  return worst;
}

double inside_length(const TetTraversal& m, const ViewRay& r, TraversalStats* stats = nullptr) {
  RayTrace t;
  m.trace(r, t, stats);
  double len = 0.0;
  for (const CellCrossing& c : t.crossings) len += c.t_out - c.t_in;
  return len;
}

// A double pyramid over the square [-1,1]^2 x {0}: apex a = (0,0,1) above, b = (0,0,-1) below.
// The upper half is cut along the diagonal p0-p2, the lower along p1-p3, and the flat tet
// (p0,p1,p2,p3) joins the two triangulations (what a Delaunay mesher leaves between four
// cospherical points). `lift` raises p2 to make that tet a sliver instead of exactly flat.
TetMesh double_pyramid(double lift) {
  TetMesh m;
  m.points = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, lift), Vec3(-1, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  for (const Vec3& p : m.points) m.scalars.push_back(0.5 + 0.3 * p.x() - 0.2 * p.y() + 0.4 * p.z());
  m.tets = {{4, 0, 1, 2}, {4, 0, 2, 3}, {5, 0, 1, 3}, {5, 1, 2, 3}, {0, 1, 2, 3}};
  return m;
}

}  // namespace

TEST_CASE("The Kuhn split of a voxel grid: 6 tets per cell, equal volumes, positively oriented", "[mesh][repair]") {
  const Vec3 lo(-1, -1, -1), hi(1, 1, 1);
  const TetMesh m = structured_box_mesh(lo, hi, 2, 3, 4);
  REQUIRE(m.tets.size() == 6u * 2 * 3 * 4);
  const double cell6 = (hi - lo).prod() / (2 * 3 * 4);  // 6 V of a tet = cell volume (6 tets/cell)
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    CHECK(classify_tet(m, i) == TetShape::Positive);
    CHECK(std::fabs(signed_volume6(m, i) - cell6) <= 1e-15 * cell6 * 8);
  }
  // As the split is written before reorient_tets (the six permutations of the axes, half of them
  // odd), every other tet is inverted: reading such a mesh reorients exactly those.
  TetMesh written = m;
  for (std::size_t i = 0; i < written.tets.size(); i += 2) std::swap(written.tets[i][0], written.tets[i][1]);
  const TetRepairs r = repair_tet_mesh(written, "kuhn");
  CHECK(r.tets_read == static_cast<long>(m.tets.size()));
  CHECK(r.reoriented == static_cast<long>(m.tets.size() / 2));
  CHECK(r.zero_volume == 0);
  CHECK(r.slivers == 0);
}

TEST_CASE("Mixed orientation: the mesh as written and reoriented give the same intensities to 1e-14", "[mesh][repair]") {
  // linear-box: a jittered Kuhn split of [-1,1]^3, n = 3 (1,296 tets). Every other tet is written
  // with an odd permutation (swap points 0 and 1, or 1 and 3), so after repair the tet's points are
  // in a different order than in the original: the fit of Eq. 9 sees them in another order.
  const GeneratedMesh g = generate_mesh("linear-box", 3, 7);
  TetMesh mixed = g.mesh;
  for (std::size_t i = 0; i < mixed.tets.size(); ++i) {
    if (i % 2 == 0) std::swap(mixed.tets[i][0], mixed.tets[i][1]);
    if (i % 4 == 1) std::swap(mixed.tets[i][1], mixed.tets[i][3]);
  }
  TetMesh strict_copy = mixed;
  CHECK_THROWS_WITH(validate_tet_mesh(strict_copy, "m"), Catch::StartsWith("m: tets[0]: inverted tetrahedron"));
  const TetRepairs r = repair_tet_mesh(mixed, "m");
  CHECK(r.reoriented == static_cast<long>((g.mesh.tets.size() + 1) / 2 + g.mesh.tets.size() / 4));
  validate_tet_mesh(mixed, "m");  // now passes the strict check
  const TetTraversal original(g.mesh, "original"), repaired(mixed, "repaired");
  const TransferFunctions tf = rayint::test::mesh_field_tf();  // the integrator keeps a reference to it
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  long segments = 0;
  const double worst = max_abs_difference(original, repaired, random_rays(3000, 2026), *exact, &segments);
  // Measured max |difference| over 3000 rays (seed 2026, ~14 segments each): printed here,
  // reported in README "Meshes as they come".
  WARN("mixed orientation: max |I_written - I_reoriented| = " << worst << " over 3000 rays, " << segments
                                                              << " segments");
  CHECK(segments > 10000);
  CHECK(worst <= test::Tolerances::reorient_abs);
}

TEST_CASE("A dropped zero-volume or sliver tet: traversal re-enters across it, nothing is lost", "[mesh][repair]") {
  for (const double lift : {0.0, 1e-13}) {
    INFO("lift " << lift);
    TetMesh m = double_pyramid(lift);
    TetMesh strict = m;
    reorient_tets(strict);  // the halves are written in both orders; the flat tet stays refused
    CHECK_THROWS_WITH(validate_tet_mesh(strict, "dp"), Catch::StartsWith("dp: tets[4]: degenerate tetrahedron"));
    const TetRepairs r = repair_tet_mesh(m, "dp");
    CHECK(r.zero_volume == (lift == 0.0 ? 1 : 0));
    CHECK(r.slivers == (lift == 0.0 ? 0 : 1));
    CHECK(m.tets.size() == 4);
    const TetTraversal mesh(m, "dp");
    TraversalStats stats;
    // Vertical rays on a grid that includes the diagonals and the axes (edges of the halves).
    int rays = 0;
    double worst = 0.0;
    for (int i = -8; i <= 8; ++i)
      for (int j = -8; j <= 8; ++j) {
        const double x = i / 8.0 * 0.999, y = j / 8.0 * 0.999;
        for (const double dz : {-1.0, 1.0}) {
          const double chord = 2.0 * (1.0 - std::max(std::fabs(x), std::fabs(y)));
          const double got = inside_length(mesh, ViewRay{Vec3(x, y, -3 * dz), Vec3(0, 0, dz)}, &stats);
          // With a lift the upper half is taller by at most the lift under p2's corner.
          worst = std::max(worst, std::fabs(got - chord));
          ++rays;
        }
      }
    CHECK(worst <= 1e-14 + lift);
    CHECK(stats.budget_exhausted == 0);
    // Oblique rays: the traced length equals the chord through the two halves (each a convex
    // pyramid), computed independently as the clip against the 8 face planes of the double pyramid.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-0.9, 0.9);
    for (int k = 0; k < 500; ++k) {
      const Vec3 target(u(rng) * 0.5, u(rng) * 0.5, u(rng) * 0.4);
      const Vec3 o(u(rng), u(rng), 3.0);
      const Vec3 d = (target - o).normalized();
      double t0 = -1e300, t1 = 1e300;
      // The double pyramid is max(|x|, |y|) + |z| <= 1: the 8 half-spaces +-x +-z <= 1, +-y +-z <= 1.
      for (const double sx : {-1.0, 1.0})
        for (const double sz : {-1.0, 1.0})
          for (int axis = 0; axis < 2; ++axis) {
            Vec3 n = Vec3::Zero();
            n[axis] = sx;
            n.z() = sz;
            const double num = 1.0 - n.dot(o), den = n.dot(d);
            if (den > 0) t1 = std::min(t1, num / den);
            else if (den < 0) t0 = std::max(t0, num / den);
          }
      const double chord = std::max(0.0, t1 - t0);
      CHECK(std::fabs(inside_length(mesh, ViewRay{o, d}) - chord) <= 1e-13 + 10 * lift);
    }
  }
}

TEST_CASE("Repair counts repeated indices as zero volume, and a mesh of only degenerate tets is refused", "[mesh][repair]") {
  TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.scalars.assign(4, 1.0);
  m.tets = {{0, 1, 2, 3}, {0, 0, 1, 2}, {0, 1, 3, 2}};
  const TetRepairs r = repair_tet_mesh(m, "m");
  CHECK(r.tets_read == 3);
  CHECK(r.zero_volume == 1);
  CHECK(r.reoriented == 1);
  CHECK(m.tets.size() == 2);
  TetMesh flat;
  flat.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  flat.scalars.assign(4, 1.0);
  flat.tets = {{0, 1, 2, 3}};
  CHECK_THROWS_WITH(repair_tet_mesh(flat, "f.vtk", MeshFieldNames{"POINTS", "POINT_DATA", "CELLS"}),
                    "f.vtk: CELLS: every tetrahedron is degenerate (1 zero-volume, 0 slivers): nothing to traverse");
}

TEST_CASE("Mesh cases: default reorients and counts, --strict-mesh refuses", "[mesh][repair]") {
  const std::string text = R"({"name": "x", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,1]], "scalars": [0, 1, 2, 3, 1],
             "tets": [[0,1,3,2],[1,2,3,4],[0,0,1,2]]},
    "rays": [{"origin": [0.2, 0.2, 5], "direction": [0, 0, -1]}]})";
  std::optional<TetRepairs> repairs;
  const Case c = parse_case_text(text, "c.json", {}, &repairs);
  REQUIRE(repairs);
  CHECK(repairs->tets_read == 3);
  CHECK(repairs->reoriented == 1);
  CHECK(repairs->zero_volume == 1);
  // Down x = y = 0.2: z in [0, 0.6] in the first tet, [0.6, 1] in the second (x + y - z <= 1 ...).
  REQUIRE(c.rays[0].segments.size() == 2);
  CHECK(c.rays[0].segments[0].length == Approx(0.6).epsilon(1e-15));
  CHECK(c.rays[0].segments[1].length == Approx(0.4).epsilon(1e-15));
  CHECK_THROWS_WITH(parse_case_text(text, "c.json", MeshReadOptions{true}),
                    Catch::StartsWith("c.json: mesh.tets[0]: inverted tetrahedron"));
}
