// VTK's quadratic cells in their own isoparametric interpolation, curved ones included
// (cells/quadratic_isoparametric.hpp, LinearCellIntegrator::integrate(QuadraticCell)): validity,
// inverse map, ray-patch hits (watertight on shared curved faces), chords, and the integral
// against the independent 50-digit reference (reference/cell_reference.hpp, ids 24-27, 29, 32).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/quadratic_isoparametric.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "rayint/studies/own_cells_eval.hpp"
#include "cell_checks.hpp"
#include "cell_samples.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::QuadraticCellTolerances;

namespace {

const std::array<QuadraticCellType, 6> kTypes = {QuadraticCellType::tetra, QuadraticCellType::hexahedron,
                                                 QuadraticCellType::wedge, QuadraticCellType::triquadratic_hexahedron,
                                                 QuadraticCellType::biquadratic_wedge, QuadraticCellType::pyramid};

// VTK's reference nodes times 2, corners perturbed by up to `noise`, every mid-edge node at its
// edge's midpoint plus a displacement of up to `bend` of the edge length (a curved cell), every
// face or cell centre node (27- and 18-node cells) at the corners' linear map of its reference
// point plus up to `bend` of the cell's size, values random in [0, 1]; mirrored (z -> -z) on
// request (the other orientation).
QuadraticCell random_cell(QuadraticCellType type, std::mt19937& rng, double noise, double bend, bool mirror = false) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  const std::vector<Vec3>& ref = quadratic_reference_nodes(type);
  const int corners = linear_node_count(quadratic_corner_type(type));
  std::vector<Vec3> nodes(ref.size(), Vec3::Zero());
  std::vector<char> set(ref.size(), 0);
  for (int i = 0; i < corners; ++i)
    nodes[static_cast<std::size_t>(i)] = 2.0 * ref[static_cast<std::size_t>(i)] + 2.0 * noise * Vec3(u(rng), u(rng), u(rng));
  for (int f = 0; f < quadratic_face_count(type); ++f) {
    const QuadraticFaceNodes q = quadratic_face(type, f);
    for (int k = 0; k < q.count; ++k) {
      const Vec3& a = nodes[static_cast<std::size_t>(q.corner[static_cast<std::size_t>(k)])];
      const Vec3& b = nodes[static_cast<std::size_t>(q.corner[static_cast<std::size_t>((k + 1) % q.count)])];
      const auto mid = static_cast<std::size_t>(q.mid[static_cast<std::size_t>(k)]);
      if (set[mid]) continue;  // set from another face
      set[mid] = 1;
      nodes[mid] = 0.5 * (a + b) + bend * (b - a).norm() * Vec3(u(rng), u(rng), u(rng));
    }
  }
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (static_cast<int>(i) < corners || set[i]) continue;
    double N[kMaxLinearNodes];
    linear_shape_functions(quadratic_corner_type(type), ref[i], N);
    for (int c = 0; c < corners; ++c) nodes[i] += N[c] * nodes[static_cast<std::size_t>(c)];
    nodes[i] += bend * 2.0 * Vec3(u(rng), u(rng), u(rng));
  }
  std::vector<double> values;
  for (Vec3& x : nodes) {
    if (mirror) x[2] = -x[2];
    values.push_back(v(rng));
  }
  return make_quadratic_cell(type, nodes, values);
}

// random_cell again until the map is one-to-one (a random bend of a tet10 can fold it: at the
// centroid its Jacobian depends on the mid-edge nodes alone); make_quadratic_cell decides.
QuadraticCell valid_cell(QuadraticCellType type, std::mt19937& rng, double noise, double bend, bool mirror = false) {
  for (int attempt = 0;; ++attempt) {
    try {
      return random_cell(type, rng, noise, bend, mirror);
    } catch (const std::invalid_argument&) {
      if (attempt == 50) throw;
    }
  }
}

Vec3 random_inside(QuadraticCellType type, std::mt19937& rng) {
  return test::random_inside(quadratic_corner_type(type), rng);
}

}  // namespace

TEST_CASE("quadratic cells: inverse map round trip on curved cells in both orientations", "[cells][quadratic][isoparametric]") {
  std::mt19937 rng(7);
  for (QuadraticCellType type : kTypes)
    for (bool mirror : {false, true})
      for (int k = 0; k < 5; ++k) {
        const QuadraticCell cell = valid_cell(type, rng, 0.1, 0.15, mirror);
        CHECK(cell.orientation == (mirror ? -1 : 1));
        CHECK_FALSE(cell.affine);
        for (int j = 0; j < 10; ++j) {
          const Vec3 p = random_inside(type, rng);
          const InverseMap m = inverse_map(cell, cell_position(cell, p));
          INFO(quadratic_cell_name(type) << " mirror " << mirror << " p " << p.transpose() << " found " << m.p.transpose());
          REQUIRE(m.converged);
          CHECK((m.p - p).cwiseAbs().maxCoeff() <= QuadraticCellTolerances::round_trip_abs);
        }
      }
}

TEST_CASE("quadratic cells: a folded cell is refused, an affine one detected", "[cells][quadratic][isoparametric]") {
  std::mt19937 rng(3);
  for (QuadraticCellType type : kTypes) {
    // Straight edges: affine, the exact linear inverse.
    std::vector<Vec3> nodes;
    std::vector<double> values;
    Eigen::Matrix3d A;
    A << 2.0, 0.3, -0.2, 0.1, 1.5, 0.4, -0.3, 0.2, 1.8;
    for (const Vec3& r : quadratic_reference_nodes(type)) {
      nodes.push_back(Vec3(0.5, -1.0, 2.0) + A * r);
      values.push_back(r.sum());
    }
    if (type == QuadraticCellType::pyramid) {
      // Never affine (the apex is a collapsed face): a straight pyramid, mid-edge nodes at the
      // midpoints of its edges, is valid and not affine.
      const int edges[8][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
      for (int e = 0; e < 8; ++e)
        nodes[static_cast<std::size_t>(5 + e)] = 0.5 * (nodes[static_cast<std::size_t>(edges[e][0])] + nodes[static_cast<std::size_t>(edges[e][1])]);
      CHECK_FALSE(make_quadratic_cell(type, nodes, values).affine);
    } else {
      const QuadraticCell affine = make_quadratic_cell(type, nodes, values);
      CHECK(affine.affine);
    }
    // A mid-edge node pulled through the opposite corner folds the map.
    const QuadraticFaceNodes f = quadratic_face(type, 0);
    const auto mid = static_cast<std::size_t>(f.mid[0]);
    const Vec3 a = nodes[static_cast<std::size_t>(f.corner[0])], b = nodes[static_cast<std::size_t>(f.corner[1])];
    nodes[mid] = a + 1.5 * (b - a);  // beyond b: the edge runs back on itself
    INFO(quadratic_cell_name(type));
    CHECK_THROWS_WITH(make_quadratic_cell(type, nodes, values), Catch::Contains("not one-to-one"));
  }
}

TEST_CASE("quadratic cells: rays aimed at points of curved faces hit them", "[cells][quadratic][isoparametric]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  for (QuadraticCellType type : kTypes) {
    const QuadraticCell cell = valid_cell(type, rng, 0.1, 0.15);
    for (int f = 0; f < quadratic_face_count(type); ++f) {
      const QuadraticFacePatch patch = canonical_quadratic_face(cell, f);
      for (int k = 0; k < 10; ++k) {
        double a = u(rng), b = u(rng);
        if (patch.count == 3 && a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        const Vec3 target = patch_point(patch.node, patch.count, patch.centre, a, b);
        const Vec3 dir = Vec3(w(rng), w(rng), w(rng)).normalized();
        const ViewRay ray{target - 5.0 * dir, dir};
        const std::vector<PatchHit> hits = intersect_quadratic_face(patch.node, patch.count, patch.centre, ray);
        INFO(quadratic_cell_name(type) << " face " << f << " (u, v) = (" << a << ", " << b << ")");
        REQUIRE_FALSE(hits.empty());
        double best = 1e300;
        for (const PatchHit& h : hits) best = std::min(best, (ray.origin + h.t * ray.direction - target).norm());
        CHECK(best <= QuadraticCellTolerances::patch_hit_abs);
      }
    }
  }
}

TEST_CASE("quadratic cells: two curved hexahedra sharing a curved face, the exit of one is the entry of the other bit for bit", "[cells][quadratic][isoparametric]") {
  for (const QuadraticCellType type : {QuadraticCellType::hexahedron, QuadraticCellType::triquadratic_hexahedron}) {
  INFO(quadratic_cell_name(type));
  // Cell A: [0,2] x [0,2] x [0,2] with curved mid-edge nodes; cell B: A's face x = 2 shared, B
  // extends to x = 4. The shared face's nodes are the same points in both, listed by each cell
  // in its own local order.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> w(-0.25, 0.25), v(0.0, 1.0);
  // Global points: a 3 x 3 x 3 lattice of (0, 1, 2, 3, 4) x (0, 1, 2) x (0, 1, 2), 5 x 3 x 3,
  // every non-corner lattice point moved (mid-edge nodes, and the face and cell centres of the
  // 27-node cells).
  auto gid = [](int i, int j, int k) { return static_cast<std::int64_t>(i + 5 * (j + 3 * k)); };
  std::vector<Vec3> pts(45);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        Vec3 x(i, j, k);
        if (i % 2 == 1 || j == 1 || k == 1) x += Vec3(w(rng), w(rng), w(rng));
        pts[static_cast<std::size_t>(gid(i, j, k))] = x;
      }
  std::vector<double> values(45);
  for (double& x : values) x = v(rng);
  const std::vector<Vec3>& ref = quadratic_reference_nodes(type);
  std::vector<QuadraticCell> cells;
  std::vector<std::array<std::int64_t, kMaxQuadraticNodes>> ids(2);
  for (int c = 0; c < 2; ++c) {
    std::vector<Vec3> nodes;
    std::vector<double> vals;
    for (std::size_t n = 0; n < ref.size(); ++n) {
      const Vec3& r = ref[n];
      const std::int64_t g = gid(2 * c + static_cast<int>(2 * r[0]), static_cast<int>(2 * r[1]), static_cast<int>(2 * r[2]));
      ids[static_cast<std::size_t>(c)][n] = g;
      nodes.push_back(pts[static_cast<std::size_t>(g)]);
      vals.push_back(values[static_cast<std::size_t>(g)]);
    }
    cells.push_back(make_quadratic_cell(type, nodes, vals));
  }
  int shared = 0;
  for (int k = 0; k < 60; ++k) {
    // Rays through random points of the shared face, and through its edges and corners.
    const double a = k < 8 ? (k % 2) : v(rng), b = k < 8 ? ((k / 2) % 2) : (k < 16 ? 0.5 : v(rng));
    const Vec3 target(2.0 + 0.2 * w(rng), a * 2.0, b * 2.0);
    const Vec3 eye(-3.0, 1.0 + 4 * w(rng), 1.0 + 4 * w(rng));
    const ViewRay ray{eye, (target - eye).normalized()};
    const Chord A = quadratic_chord(cells[0], ray, ids[0].data());
    const Chord B = quadratic_chord(cells[1], ray, ids[1].data());
    REQUIRE_FALSE(A.failed);
    REQUIRE_FALSE(B.failed);
    // The face x = 2 is face 1 of A (nodes 1, 2, 6, 5) and face 0 of B (0, 4, 7, 3): hits equal.
    std::vector<double> ha, hb;
    for (const ChordFaceHit& h : A.hits)
      if (h.face == 1) ha.push_back(h.t);
    for (const ChordFaceHit& h : B.hits)
      if (h.face == 0) hb.push_back(h.t);
    CHECK(ha == hb);
    // A ray that leaves A through the shared face enters B there: A's piece ends exactly
    // where B's begins.
    if (!A.intervals.empty() && std::find(ha.begin(), ha.end(), A.intervals.back().t_far) != ha.end()) {
      REQUIRE_FALSE(B.intervals.empty());
      CHECK(A.intervals.back().t_far == B.intervals.front().t_near);
      ++shared;
    }
  }
  CHECK(shared >= 30);
  }
}

TEST_CASE("quadratic cells: the double path against the 50-digit reference on curved cells", "[cells][quadratic][isoparametric][reference]") {
  test::ReferenceChordSweep sweep(QuadraticCellTolerances::reference_rel, 2030);
  for (QuadraticCellType type : kTypes)
    for (bool mirror : {false, true})
      for (int k = 0; k < 3; ++k) {
        const QuadraticCell cell = valid_cell(type, sweep.rng, 0.1, 0.1 + 0.1 * sweep.uniform(), mirror);
        const ViewRay ray = sweep.ray_at(cell_position(cell, random_inside(type, sweep.rng)));
        const Chord ch = quadratic_chord(cell, ray);
        REQUIRE_FALSE(ch.failed);
        REQUIRE_FALSE(ch.intervals.empty());
        const std::string label = std::string(quadratic_cell_name(type)) + " mirror " + std::to_string(mirror);
        for (const CellPieceIntegral& d : sweep.check(cell, ray, ch, label)) {
          INFO(label);
          CHECK(d.path == CellPath::isoparametric);
        }
      }
  WARN("quadratic cells vs 50-digit reference: worst relative error " << sweep.worst << " over " << sweep.chords
                                                                       << " chords");
  CHECK(sweep.chords >= 30);
}

TEST_CASE("quadratic pyramid: distorted cells against the 50-digit reference, rays through the apex region too", "[cells][quadratic][isoparametric][reference][pyramid]") {
  // Corners perturbed by up to 0.15 of the base (and the apex), mid-edge nodes off their edges by
  // up to 20 % of the edge (curved faces), both orientations; half the rays aimed at points near
  // the apex (t >= 0.8, where det J -> 0 as (1 - t)^2).
  test::ReferenceChordSweep sweep(QuadraticCellTolerances::reference_rel, 2729);
  const QuadraticCellType type = QuadraticCellType::pyramid;
  for (bool mirror : {false, true})
    for (int k = 0; k < 10; ++k) {
      const QuadraticCell cell = valid_cell(type, sweep.rng, 0.15, 0.1 + 0.1 * sweep.uniform(), mirror);
      Vec3 p = random_inside(type, sweep.rng);
      if (k % 2 == 1) p[2] = 0.8 + 0.15 * sweep.uniform();
      const ViewRay ray = sweep.ray_at(cell_position(cell, p));
      const Chord ch = quadratic_chord(cell, ray);
      INFO("cell " << k << " mirror " << mirror);
      REQUIRE_FALSE(ch.failed);
      REQUIRE_FALSE(ch.intervals.empty());
      sweep.check(cell, ray, ch, quadratic_cell_name(type));
    }
  WARN("distorted quadratic pyramids vs 50-digit reference: worst relative error " << sweep.worst << " over "
                                                                                    << sweep.chords << " chords");
  CHECK(sweep.chords >= 20);
}
