// The linear VTK cells in their own interpolation (cells/linear_cells.hpp, cells/cell_integral.hpp):
// shape functions against VTK itself (fixture written by VTK 9.1, scripts/cells/vtk_shape_fixture.py),
// partition of unity, the inverse map, ray-face hits (watertight on shared faces), chords through
// edges and vertices, and the integral against independent paths and the 50-digit reference
// (reference/cell_reference.hpp).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "test_paths.hpp"
#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/chord_scalar.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/vtk_split.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "rayint/reference/reference.hpp"
#include "cell_checks.hpp"
#include "cell_samples.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using rayint::test::LinearCellTolerances;
using rayint::test::random_inside;

namespace {

const std::array<LinearCellType, 5> kTypes = {LinearCellType::tetra, LinearCellType::voxel,
                                              LinearCellType::hexahedron, LinearCellType::wedge,
                                              LinearCellType::pyramid};

// A cell of the type: its reference nodes times 2, each perturbed by up to `noise` (edge
// fraction), optionally mirrored (z -> -z, negative Jacobian), values random in [0, 1].
LinearCell random_cell(LinearCellType type, std::mt19937& rng, double noise, bool mirror = false) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  std::vector<Vec3> nodes;
  std::vector<double> values;
  for (const Vec3& r : linear_reference_nodes(type)) {
    Vec3 x = 2.0 * r + 2.0 * noise * Vec3(u(rng), u(rng), u(rng));
    if (mirror) x[2] = -x[2];
    nodes.push_back(x);
    values.push_back(v(rng));
  }
  return make_linear_cell(type, nodes, values);
}

// An undistorted random cell; a hexahedron sheared into a parallelepiped (still affine, but no
// longer a box).
LinearCell affine_cell(LinearCellType type, std::mt19937& rng) {
  LinearCell cell = random_cell(type, rng, 0.0);
  if (type != LinearCellType::hexahedron) return cell;
  const Vec3 shear(0.3, -0.2, 0.1);
  std::vector<Vec3> nodes;
  std::vector<double> values;
  for (std::size_t i = 0; i < 8; ++i) {
    nodes.push_back(cell.x[i] + cell.x[i][2] * shear);
    values.push_back(cell.value[i]);
  }
  return make_linear_cell(type, nodes, values);
}

// affine_cell with a ray from a random direction through its centre and the chord's one interval.
struct AffineSample {
  LinearCell cell;
  ViewRay ray;
  double t_near, t_far;
};

AffineSample affine_sample(LinearCellType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  LinearCell cell = affine_cell(type, rng);
  REQUIRE(cell.affine);
  const Vec3 target = cell_position(cell, linear_reference_centre(type));
  const Vec3 eye = target + 6.0 * Vec3(u(rng), u(rng), u(rng)).normalized();
  const ViewRay ray{eye, (target - eye).normalized()};
  const Chord ch = chord(cell, ray);
  REQUIRE(ch.intervals.size() == 1);
  return {std::move(cell), ray, ch.intervals[0].t_near, ch.intervals[0].t_far};
}

}  // namespace

TEST_CASE("linear cells: shape functions, derivatives and positions match VTK's own", "[cells][isoparametric]") {
  std::ifstream in(RAYINT_SOURCE_DIR + "/tests/fixtures/cells/vtk_linear_cells.json");
  REQUIRE(in.good());
  const nlohmann::json doc = nlohmann::json::parse(in);
  double worst_weight = 0.0, worst_deriv = 0.0, worst_x = 0.0;
  int samples = 0;
  std::array<int, 15> per_type{};
  for (const auto& c : doc.at("cells")) {
    LinearCellType type{};
    REQUIRE(linear_cell_type_from_vtk(c.at("vtk_id").get<int>(), type));
    std::vector<Vec3> nodes;
    for (const auto& x : c.at("nodes")) nodes.emplace_back(x[0].get<double>(), x[1].get<double>(), x[2].get<double>());
    const std::vector<double> zeros(nodes.size(), 0.0);
    const LinearCell cell = make_linear_cell(type, nodes, zeros);
    const int n = linear_node_count(type);
    for (const auto& s : c.at("samples")) {
      const Vec3 p(s["pcoords"][0].get<double>(), s["pcoords"][1].get<double>(), s["pcoords"][2].get<double>());
      double N[kMaxLinearNodes], dN[3 * kMaxLinearNodes];
      linear_shape_functions(type, p, N);
      linear_shape_derivatives(type, p, dN);
      for (int i = 0; i < n; ++i) worst_weight = std::max(worst_weight, std::abs(N[i] - s["weights"][i].get<double>()));
      for (int i = 0; i < 3 * n; ++i) worst_deriv = std::max(worst_deriv, std::abs(dN[i] - s["derivs"][i].get<double>()));
      const Vec3 x = cell_position(cell, p);
      for (int k = 0; k < 3; ++k) worst_x = std::max(worst_x, std::abs(x[k] - s["x"][k].get<double>()));
      ++samples;
      ++per_type[static_cast<std::size_t>(static_cast<int>(type))];
    }
  }
  INFO("samples " << samples << ", worst |dN| " << worst_weight << ", |d dN| " << worst_deriv << ", |dx| " << worst_x);
  for (LinearCellType t : kTypes) CHECK(per_type[static_cast<std::size_t>(static_cast<int>(t))] >= 40);
  CHECK(worst_weight <= LinearCellTolerances::vtk_abs);
  CHECK(worst_deriv <= LinearCellTolerances::vtk_abs);
  CHECK(worst_x <= LinearCellTolerances::vtk_abs);
}

TEST_CASE("linear cells: partition of unity, nodal values and derivative sums", "[cells][isoparametric]") {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  for (LinearCellType type : kTypes) {
    const int n = linear_node_count(type);
    const std::vector<Vec3>& ref = linear_reference_nodes(type);
    for (int i = 0; i < n; ++i) {
      double N[kMaxLinearNodes];
      linear_shape_functions(type, ref[static_cast<std::size_t>(i)], N);
      for (int j = 0; j < n; ++j) CHECK(std::abs(N[j] - (i == j ? 1.0 : 0.0)) <= LinearCellTolerances::unity_abs);
    }
    for (int k = 0; k < 200; ++k) {
      const Vec3 p(u(rng), u(rng), u(rng));
      double N[kMaxLinearNodes], dN[3 * kMaxLinearNodes];
      linear_shape_functions(type, p, N);
      linear_shape_derivatives(type, p, dN);
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += N[i];
      CHECK(std::abs(sum - 1.0) <= LinearCellTolerances::unity_abs);
      for (int j = 0; j < 3; ++j) {
        double d = 0.0;
        for (int i = 0; i < n; ++i) d += dN[j * n + i];
        CHECK(std::abs(d) <= LinearCellTolerances::unity_abs);
        // Derivative against a central difference (h = 1e-6: error ~1e-10 for these
        // polynomials of degree <= 3).
        Vec3 pp = p, pm = p;
        pp[j] += 1e-6;
        pm[j] -= 1e-6;
        double Np[kMaxLinearNodes], Nm[kMaxLinearNodes];
        linear_shape_functions(type, pp, Np);
        linear_shape_functions(type, pm, Nm);
        for (int i = 0; i < n; ++i) CHECK(std::abs((Np[i] - Nm[i]) / 2e-6 - dN[j * n + i]) <= 1e-8);
      }
    }
  }
}

TEST_CASE("linear cells: inverse map round trip on distorted cells in both orientations", "[cells][isoparametric]") {
  std::mt19937 rng(7);
  for (LinearCellType type : kTypes)
    for (bool mirror : {false, true})
      for (int c = 0; c < 20; ++c) {
        const LinearCell cell = random_cell(type, rng, 0.15, mirror);
        for (int k = 0; k < 20; ++k) {
          const Vec3 p = random_inside(type, rng);
          const InverseMap m = inverse_map(cell, cell_position(cell, p));
          INFO(linear_cell_name(type) << " mirror " << mirror << " iterations " << m.iterations);
          REQUIRE(m.converged);
          CHECK((m.p - p).cwiseAbs().maxCoeff() <= LinearCellTolerances::round_trip_abs);
        }
      }
}

TEST_CASE("linear cells: an affine cell's scalar along a chord multiplied out equals the nodal form", "[cells][isoparametric]") {
  // affine_chord_chebyshev's cubic (chord_scalar.hpp) against cell_scalar at the inverse-mapped
  // ray points, for voxels, sheared parallelepiped hexahedra and wedges: within its own rounding
  // scale plus 8 ulps of max |f_i| (cell_scalar's rounding); and the scale is that small (<= 64
  // ulps of max |f_i|, the tail target of cell_integral.hpp).
  std::mt19937 rng(23);
  int points = 0;
  for (LinearCellType type : {LinearCellType::voxel, LinearCellType::hexahedron, LinearCellType::wedge}) {
    for (int k = 0; k < 20; ++k) {
      const auto [cell, ray, t_near, t_far] = affine_sample(type, rng);
      const double a = t_near, b = t_far;
      std::array<double, 4> c{};
      const double rounding = affine_chord_chebyshev(cell, ray, a, b, c);
      double f_max = 0.0;
      for (int i = 0; i < linear_node_count(type); ++i) f_max = std::max(f_max, std::abs(cell.value[static_cast<std::size_t>(i)]));
      CHECK(rounding <= 64 * 2.220446049250313e-16 * f_max);
      for (int j = 0; j <= 16; ++j) {
        const double x = -1.0 + j / 8.0;
        const double T[4] = {1.0, x, 2 * x * x - 1, 4 * x * x * x - 3 * x};
        const double series = c[0] * T[0] + c[1] * T[1] + c[2] * T[2] + c[3] * T[3];
        const Vec3 world = ray.origin + (0.5 * (a + b) + 0.5 * (b - a) * x) * ray.direction;
        const double nodal = cell_scalar(cell, cell.affine_inverse * (world - cell.affine_origin));
        INFO(linear_cell_name(type) << " x " << x);
        CHECK(std::abs(series - nodal) <= rounding + 8 * 2.220446049250313e-16 * f_max);
        ++points;
      }
    }
  }
  CHECK(points == 3 * 20 * 17);
}

TEST_CASE("linear cells: affine detection", "[cells][isoparametric]") {
  std::mt19937 rng(3);
  // A parallelepiped hexahedron from its axes is affine; moving one node by 1e-6 is not.
  const Vec3 o(0.3, -1.0, 2.0), a(1.0, 0.2, 0.1), b(-0.3, 1.1, 0.2), c(0.1, 0.3, 0.9);
  std::vector<Vec3> nodes;
  for (const Vec3& r : linear_reference_nodes(LinearCellType::hexahedron)) nodes.push_back(o + r[0] * a + r[1] * b + r[2] * c);
  const std::vector<double> values(8, 0.5);
  CHECK(make_linear_cell(LinearCellType::hexahedron, nodes, values).affine);
  nodes[6][1] += 1e-6;
  CHECK_FALSE(make_linear_cell(LinearCellType::hexahedron, nodes, values).affine);
  CHECK(random_cell(LinearCellType::tetra, rng, 0.2).affine);
  CHECK_FALSE(random_cell(LinearCellType::pyramid, rng, 0.0).affine);  // VTK's pyramid map never is
  CHECK_FALSE(random_cell(LinearCellType::hexahedron, rng, 0.2).affine);
}

TEST_CASE("linear cells: a shared bilinear face gives bit-identical hits from both cells", "[cells][isoparametric]") {
  // Two distorted hexahedra sharing the face of global nodes 1 2 6 5 (cell A's face 1) = cell B's
  // nodes 0 3 7 4 (its face 0), listed by B in a different cyclic start and orientation.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.25, 0.25), w(0.0, 1.0);
  std::vector<Vec3> pts;
  for (int k = 0; k < 12; ++k) {  // a 3 x 2 x 2 block of nodes, x fastest
    const int i = k % 3, j = (k / 3) % 2, l = k / 6;
    pts.emplace_back(i + u(rng), j + u(rng), l + u(rng));
  }
  auto id = [](int i, int j, int l) { return static_cast<std::int64_t>(i + 3 * j + 6 * l); };
  const std::array<std::int64_t, 8> ids_a = {id(0, 0, 0), id(1, 0, 0), id(1, 1, 0), id(0, 1, 0),
                                             id(0, 0, 1), id(1, 0, 1), id(1, 1, 1), id(0, 1, 1)};
  const std::array<std::int64_t, 8> ids_b = {id(1, 0, 0), id(2, 0, 0), id(2, 1, 0), id(1, 1, 0),
                                             id(1, 0, 1), id(2, 0, 1), id(2, 1, 1), id(1, 1, 1)};
  auto make = [&](const std::array<std::int64_t, 8>& ids) {
    std::vector<Vec3> nodes;
    std::vector<double> values;
    for (std::int64_t g : ids) {
      nodes.push_back(pts[static_cast<std::size_t>(g)]);
      values.push_back(0.1 * static_cast<double>(g));
    }
    return make_linear_cell(LinearCellType::hexahedron, nodes, values);
  };
  const LinearCell A = make(ids_a), B = make(ids_b);
  int shared = 0;
  for (int k = 0; k < 500; ++k) {
    // Rays from the left toward random points of the shared patch.
    const double s = w(rng), t = w(rng);
    const Vec3 target = (1 - s) * (1 - t) * pts[1] + s * (1 - t) * pts[4] + s * t * pts[10] + (1 - s) * t * pts[7];
    const Vec3 eye(-3.0 + u(rng), 0.5 + 4 * u(rng), 0.5 + 4 * u(rng));
    const ViewRay ray{eye, (target - eye).normalized()};
    const Chord ca = chord(A, ray, ids_a.data()), cb = chord(B, ray, ids_b.data());
    REQUIRE_FALSE(ca.failed);
    REQUIRE_FALSE(cb.failed);
    if (ca.intervals.size() != 1 || cb.intervals.size() != 1) continue;
    ++shared;
    CHECK(ca.intervals[0].t_far == cb.intervals[0].t_near);  // bit-identical, no gap, no overlap
  }
  CHECK(shared >= 400);
}

TEST_CASE("linear cells: rays through shared edges and vertices neither drop nor double a piece", "[cells][isoparametric]") {
  // A 2 x 2 x 2 block of distorted hexahedra (27 nodes, the centre node moved); rays through
  // the centre vertex, through interior edges and through random points: the chords of the 8
  // cells tile the block's chord.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2), w(0.0, 1.0);
  std::vector<Vec3> pts;
  auto id = [](int i, int j, int l) { return static_cast<std::int64_t>(i + 3 * j + 9 * l); };
  for (int l = 0; l < 3; ++l)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        // A coordinate moves only along an axis where the node is interior (index 1), so the
        // block's outer faces stay the planes of [0, 2]^3 and the inner faces are curved.
        const int index[3] = {i, j, l};
        Vec3 x(i, j, l);
        for (int k = 0; k < 3; ++k)
          if (index[k] == 1) x[k] += u(rng);
        pts.push_back(x);
      }
  std::vector<LinearCell> cells;
  std::vector<std::array<std::int64_t, 8>> ids;
  for (int l = 0; l < 2; ++l)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        std::array<std::int64_t, 8> g = {id(i, j, l), id(i + 1, j, l), id(i + 1, j + 1, l), id(i, j + 1, l),
                                         id(i, j, l + 1), id(i + 1, j, l + 1), id(i + 1, j + 1, l + 1), id(i, j + 1, l + 1)};
        std::vector<Vec3> nodes;
        std::vector<double> values;
        for (std::int64_t k : g) {
          nodes.push_back(pts[static_cast<std::size_t>(k)]);
          values.push_back(w(rng));
        }
        cells.push_back(make_linear_cell(LinearCellType::hexahedron, nodes, values));
        ids.push_back(g);
      }
  std::vector<Vec3> targets = {pts[static_cast<std::size_t>(id(1, 1, 1))]};
  for (std::int64_t e : {id(1, 1, 0), id(1, 0, 1), id(0, 1, 1)})  // interior edge midpoints
    targets.push_back(0.5 * (pts[static_cast<std::size_t>(e)] + pts[static_cast<std::size_t>(id(1, 1, 1))]));
  for (int k = 0; k < 40; ++k) targets.emplace_back(0.2 + 1.6 * w(rng), 0.2 + 1.6 * w(rng), 0.2 + 1.6 * w(rng));
  for (const Vec3& target : targets) {
    const Vec3 eye(-5.0 + u(rng), -4.0 + u(rng), -3.0 + u(rng));
    const ViewRay ray{eye, (target - eye).normalized()};
    std::vector<ChordInterval> all;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const Chord ch = chord(cells[c], ray, ids[c].data());
      REQUIRE_FALSE(ch.failed);
      all.insert(all.end(), ch.intervals.begin(), ch.intervals.end());
    }
    std::sort(all.begin(), all.end(), [](const ChordInterval& a, const ChordInterval& b) { return a.t_near < b.t_near; });
    REQUIRE_FALSE(all.empty());
    // The block is the unit cube scaled by 2 (outer faces planar): its chord by slab clipping.
    double t0 = -1e300, t1 = 1e300;
    for (int k = 0; k < 3; ++k) {
      const double a = (0.0 - eye[k]) / ray.direction[k], b = (2.0 - eye[k]) / ray.direction[k];
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
    }
    INFO("target " << target.transpose() << " pieces " << all.size());
    CHECK(std::abs(all.front().t_near - t0) <= 1e-12);
    CHECK(std::abs(all.back().t_far - t1) <= 1e-12);
    for (std::size_t k = 0; k + 1 < all.size(); ++k)
      CHECK(std::abs(all[k].t_far - all[k + 1].t_near) <= 1e-12 * t1);  // no gap, no overlap
  }
}

TEST_CASE("linear cells: the curved paths agree with the exact ones where both apply", "[cells][isoparametric]") {
  std::mt19937 rng(13);
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[static_cast<std::size_t>(c)] = {{0.0, 0.3, 0.55, 1.0}, {0.2, 1.5 + c, 0.4, 2.0}};
    tf.color[static_cast<std::size_t>(c)] = {{0.1, 0.6, 0.9}, {1.0, 0.2 * c, 0.7}};
  }
  const LinearCellIntegrator integrator(tf);
  int compared = 0;
  for (LinearCellType type : {LinearCellType::tetra, LinearCellType::hexahedron, LinearCellType::wedge}) {
    for (int k = 0; k < 30; ++k) {
      const auto [cell, ray, t_near, t_far] = affine_sample(type, rng);
      const CellPieceIntegral exact = integrator.integrate(cell, ray, t_near, t_far);
      const CellPieceIntegral curved =
          integrator.integrate_isoparametric(cell, ray, t_near, t_far);
      INFO(linear_cell_name(type) << ": " << exact.failure << " / " << curved.failure);
      REQUIRE(exact.converged);
      REQUIRE(curved.converged);
      CHECK(exact.path == (type == LinearCellType::tetra ? CellPath::linear_exact : CellPath::polynomial));
      CHECK(curved.path == CellPath::isoparametric);
      for (std::size_t c = 0; c < kChannels; ++c) {
        CHECK(std::abs(curved.emission[c] - exact.emission[c]) <= LinearCellTolerances::path_agreement_rel * exact.emission[c]);
        CHECK(std::abs(curved.optical_depth[c] - exact.optical_depth[c]) <=
              LinearCellTolerances::path_agreement_rel * exact.optical_depth[c]);
      }
      ++compared;
    }
  }
  CHECK(compared == 90);
}

TEST_CASE("linear cells: compositing two halves of a chord gives the whole", "[cells][isoparametric]") {
  std::mt19937 rng(17);
  const TransferFunctions tf = test::uniform_tf(test::line(0.0, 0.1, 1.0, 3.0), test::line(0.0, 1.0, 1.0, 0.2));
  const LinearCellIntegrator integrator(tf);
  for (LinearCellType type : kTypes) {
    const LinearCell cell = random_cell(type, rng, 0.15);
    const Vec3 target = cell_position(cell, linear_reference_centre(type));
    const ViewRay ray{target + Vec3(4.0, 1.0, 0.5), -Vec3(4.0, 1.0, 0.5).normalized()};
    const Chord ch = chord(cell, ray);
    REQUIRE(ch.intervals.size() == 1);
    const double a = ch.intervals[0].t_near, b = ch.intervals[0].t_far, m = 0.4 * a + 0.6 * b;
    const CellPieceIntegral whole = integrator.integrate(cell, ray, a, b);
    const CellPieceIntegral halves = composite(integrator.integrate(cell, ray, a, m), integrator.integrate(cell, ray, m, b));
    REQUIRE(whole.converged);
    REQUIRE(halves.converged);
    for (std::size_t c = 0; c < kChannels; ++c) {
      CHECK(std::abs(halves.emission[c] - whole.emission[c]) <= 1e-13 + whole.error_estimate + halves.error_estimate);
      CHECK(std::abs(halves.optical_depth[c] - whole.optical_depth[c]) <= 1e-13 * whole.optical_depth[c]);
    }
  }
}

TEST_CASE("linear cells: bad input and failures are reported, never a number", "[cells][isoparametric]") {
  const TransferFunctions tf = test::uniform_tf(test::constant(1.0), test::constant(1.0));
  const LinearCellIntegrator integrator(tf);
  std::vector<Vec3> nodes(8, Vec3::Zero());
  CHECK_THROWS_AS(make_linear_cell(LinearCellType::hexahedron, nodes, std::vector<double>(8, 0.0)), std::invalid_argument);
  CHECK_THROWS_AS(make_linear_cell(LinearCellType::wedge, nodes, std::vector<double>(8, 0.0)), std::invalid_argument);
  std::mt19937 rng(1);
  const LinearCell cell = random_cell(LinearCellType::hexahedron, rng, 0.1);
  const ViewRay ray{Vec3(0.5, 0.5, -3.0), Vec3(0.0, 0.0, 1.0)};
  const CellPieceIntegral reversed = integrator.integrate(cell, ray, 1.0, 0.0);
  CHECK_FALSE(reversed.converged);
  CHECK(std::string(reversed.failure).size() > 0);
}

// ---- The 50-digit reference (reference/cell_reference.hpp) --------------------------------

namespace {

using test::breakpoint_tf;
using test::reference_input;

double ext(const ExtendedValue& v) { return v.hi + v.lo; }

}  // namespace

TEST_CASE("cell reference: a linear scalar along the chord matches the 50-digit linear reference", "[cells][isoparametric]") {
  // Rays along x at dyadic y, z through a unit tetra, a unit hexahedron, a unit voxel and a unit
  // wedge with dyadic values: the scalar is exactly linear in t with exactly representable end
  // values, so reference_ray (reference.cpp, a different code) computes the same integral.
  const TransferFunctions tf = breakpoint_tf();
  struct Case {
    LinearCellType type;
    double y, z, x0, x1;  // the chord in x
  };
  const Case cases[] = {{LinearCellType::tetra, 0.25, 0.25, 0.0, 0.5},
                        {LinearCellType::hexahedron, 0.375, 0.625, 0.0, 1.0},
                        {LinearCellType::voxel, 0.125, 0.75, 0.0, 1.0},
                        {LinearCellType::wedge, 0.25, 0.5, 0.0, 0.75}};
  for (const Case& k : cases) {
    std::vector<Vec3> nodes = linear_reference_nodes(k.type);
    std::vector<double> values;
    for (std::size_t i = 0; i < nodes.size(); ++i) values.push_back(static_cast<double>((5 * i + 3) % 8) / 8.0);
    const LinearCell cell = make_linear_cell(k.type, nodes, values);
    const ViewRay ray{Vec3(-1.0, k.y, k.z), Vec3(1.0, 0.0, 0.0)};
    const CellReference ref = reference_cell_chord(tf, reference_input(cell, ray, 1.0 + k.x0, 1.0 + k.x1));
    // The same chord as a linear segment; the end values are exact in double (dyadic).
    const double f_far = cell_scalar(cell, Vec3(k.x1, k.y, k.z)), f_near = cell_scalar(cell, Vec3(k.x0, k.y, k.z));
    Ray lin;
    lin.segments.push_back({k.x1 - k.x0, f_far, f_near});
    const ReferenceRay lr = reference_ray(tf, lin);
    INFO(linear_cell_name(k.type) << " pieces " << ref.pieces << " degree " << ref.max_degree);
    for (std::size_t c = 0; c < kChannels; ++c) {
      CHECK(std::abs(ref.emission[c] - ext(lr.intensity[c])) <= 1e-15 * ext(lr.intensity[c]));  // both to ~30 digits, rounded to double
      CHECK(std::abs(std::exp(-ref.optical_depth[c]) - ext(lr.transmittance[c])) <= 1e-15 * ext(lr.transmittance[c]));
      CHECK(ref.emission_error[c] <= 1e-30 * ref.emission[c] + 1e-300);
      CHECK(ref.emission_error[c] > 0.0);
    }
  }
}

TEST_CASE("cell reference: the double path on distorted cells of every type, both wedge orientations", "[cells][isoparametric]") {
  // The sample of this test is small (the reference costs ~0.1 s a chord); the measured figures
  // over 200 rays per family are in reports/cells/accuracy.md (tools/cell_accuracy.cpp).
  test::ReferenceChordSweep sweep(LinearCellTolerances::reference_rel, 2029);
  for (LinearCellType type : kTypes)
    for (bool mirror : {false, true})
      for (int k = 0; k < 3; ++k) {
        const LinearCell cell = random_cell(type, sweep.rng, 0.1 + 0.2 * sweep.uniform(), mirror);
        const ViewRay ray = sweep.ray_at(cell_position(cell, random_inside(type, sweep.rng)));
        const Chord ch = chord(cell, ray);
        REQUIRE_FALSE(ch.failed);
        sweep.check(cell, ray, ch, std::string(linear_cell_name(type)) + " mirror " + std::to_string(mirror));
      }
  INFO("worst relative error " << sweep.worst << " over " << sweep.chords << " chords");
  CHECK(sweep.chords >= 30);
}

TEST_CASE("vtk split: the recorded tables give VTK's own tetrahedra on distorted cells with random ids", "[cells][isoparametric]") {
  std::ifstream in(RAYINT_SOURCE_DIR + "/tests/fixtures/cells/vtk_split_check.json");
  REQUIRE(in.good());
  const nlohmann::json doc = nlohmann::json::parse(in);
  int checked = 0;
  for (const auto& c : doc.at("cells")) {
    LinearCellType type{};
    REQUIRE(linear_cell_type_from_vtk(c.at("vtk_id").get<int>(), type));
    std::vector<std::int64_t> ids;
    for (const auto& v : c.at("ids")) ids.push_back(v.get<std::int64_t>());
    std::vector<std::array<int, 4>> mine = vtk_split(type, ids.data());
    for (auto& t : mine) std::sort(t.begin(), t.end());
    std::sort(mine.begin(), mine.end());
    std::vector<std::array<int, 4>> theirs;
    for (const auto& t : c.at("tets")) theirs.push_back({t[0].get<int>(), t[1].get<int>(), t[2].get<int>(), t[3].get<int>()});
    INFO(linear_cell_name(type));
    CHECK(mine == theirs);
    ++checked;
  }
  CHECK(checked == 200);
  // The split tiles the cell: the tets' volumes add up to the cell's (undistorted reference cells).
  for (LinearCellType type : kTypes) {
    const std::vector<Vec3>& r = linear_reference_nodes(type);
    const std::vector<std::int64_t> ids = {3, 0, 5, 1, 7, 2, 6, 4};
    std::vector<std::int64_t> use(ids.begin(), ids.begin() + linear_node_count(type));
    // ids must be a set of distinct values; the first n of the list are.
    double volume = 0.0;
    for (const auto& t : vtk_split(type, use.data()))
      volume += std::abs((r[static_cast<std::size_t>(t[1])] - r[static_cast<std::size_t>(t[0])])
                             .dot((r[static_cast<std::size_t>(t[2])] - r[static_cast<std::size_t>(t[0])])
                                      .cross(r[static_cast<std::size_t>(t[3])] - r[static_cast<std::size_t>(t[0])]))) / 6.0;
    const double expected = type == LinearCellType::tetra ? 1.0 / 6.0 : type == LinearCellType::wedge ? 0.5
                            : type == LinearCellType::pyramid ? 1.0 / 3.0 : 1.0;
    INFO(linear_cell_name(type));
    CHECK(std::abs(volume - expected) <= 1e-15);
  }
  for (LinearCellType type : {LinearCellType::hexahedron, LinearCellType::voxel})
    for (int parity : {0, 1}) CHECK(vtk_structured_split(type, parity).size() == 5);
}
