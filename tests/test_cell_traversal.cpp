// The own-interpolation traversal of meshes of linear cells (mesh/cell_traversal.hpp), on files
// that gmsh 4.8 and VTK 9.1 wrote (tests/fixtures/readers/, generate-cells.sh), tag [celltraversal]:
//  - whole rays equal the front-to-back composite of every cell's chord found independently (each
//    cell of the mesh intersected on its own, brute force) and integrated by the 50-digit cell
//    reference (reference/cell_reference.hpp), to 1e-13;
//  - rays through shared vertices and edges lose and double nothing (chord lengths against the
//    brute-force union of every cell's chord);
//  - a field linear in space on a mesh with planar boundary faces: own interpolation and VTK's
//    split are both exact, and agree;
//  - a non-convex mesh: the ray leaves and re-enters.
#include <catch2/catch.hpp>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "test_paths.hpp"
#include "cell_samples.hpp"
#include "cli_harness.hpp"
#include "bow_tie.hpp"
#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/reference/cell_reference.hpp"

using namespace rayint;

namespace {

const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/";

struct BruteChord {
  std::int32_t cell;
  double t_in, t_out;
};

// Every cell's chord on the walk ray of `trace`, each cell on its own (not the traversal),
// clipped at the eye; pieces shorter than 1e-12 (rounding at a touched vertex or edge) dropped.
std::vector<BruteChord> brute_force(const CellTraversal& m, const CellTrace& trace) {
  std::vector<BruteChord> out;
  const ViewRay ray{trace.origin, trace.direction};
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    const auto ids = m.global_ids(c);
    const Chord ch = chord(m.cell(c), ray, ids.data());
    REQUIRE_FALSE(ch.failed);
    for (const ChordInterval& iv : ch.intervals) {
      const double a = std::max(iv.t_near, trace.t_eye);
      if (iv.t_far - a > 1e-12) out.push_back({static_cast<std::int32_t>(c), a, iv.t_far});
    }
  }
  std::sort(out.begin(), out.end(), [](const BruteChord& x, const BruteChord& y) { return x.t_in < y.t_in; });
  return out;
}

double traced_length(const CellTrace& trace) {
  double s = 0.0;
  for (const auto& c : trace.chords) s += c.t_out - std::max(c.t_in, trace.t_eye) > 0 ? c.t_out - std::max(c.t_in, trace.t_eye) : 0.0;
  return s;
}

// The reference's input for the chord [a, b] of the traced ray (its walk origin and direction).
CellReferenceInput reference_input(const LinearCell& cell, const CellTrace& trace, double a, double b) {
  return test::reference_input(cell, ViewRay{trace.origin, trace.direction}, a, b);
}

// Front-to-back composite of the 50-digit chords of the brute-force list (long double).
void reference_ray(const CellTraversal& m, const TransferFunctions& tf, const CellTrace& trace,
                   const std::vector<BruteChord>& chords, Rgb& emission, Rgb& depth) {
  for (int ch = 0; ch < kChannels; ++ch) {
    long double c = 0, d = 0;
    for (const BruteChord& b : chords) {
      const CellReference r = reference_cell_chord(tf, reference_input(m.cell(static_cast<std::size_t>(b.cell)), trace, b.t_in, b.t_out));
      c += std::exp(-d) * static_cast<long double>(r.emission[static_cast<std::size_t>(ch)]);
      d += static_cast<long double>(r.optical_depth[static_cast<std::size_t>(ch)]);
    }
    emission[static_cast<std::size_t>(ch)] = static_cast<double>(c);
    depth[static_cast<std::size_t>(ch)] = static_cast<double>(d);
  }
}

// A ray from outside the mesh's box through `target`, direction from `rng`.
ViewRay ray_through(const CellTraversal& m, const Vec3& target, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 d(g(rng), g(rng), g(rng));
  d.normalize();
  const double reach = 2.0 * (m.box_max() - m.box_min()).norm();
  return {target - reach * d, d};
}

Vec3 random_inside_box(const CellTraversal& m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.1, 0.9);
  const Vec3 lo = m.box_min(), hi = m.box_max();
  return Vec3(lo.x() + u(rng) * (hi.x() - lo.x()), lo.y() + u(rng) * (hi.y() - lo.y()), lo.z() + u(rng) * (hi.z() - lo.z()));
}

// Points shared by `min_cells` or more cells (interior vertices of a block).
std::vector<Vec3> shared_points(const CellMesh& mesh, int min_cells) {
  std::vector<int> uses(mesh.points.size(), 0);
  for (std::int32_t p : mesh.connectivity) ++uses[static_cast<std::size_t>(p)];
  std::vector<Vec3> out;
  for (std::size_t p = 0; p < mesh.points.size(); ++p)
    if (uses[p] >= min_cells) out.push_back(mesh.points[p]);
  return out;
}

// The traversal's chords against the brute force: the same cells in the same order, the same end
// points to 1e-12 (pieces below 1e-12 dropped from both), and the same total length to 1e-13.
void check_chords_match(const CellTrace& trace, const std::vector<BruteChord>& brute) {
  std::vector<BruteChord> walked;
  for (const auto& c : trace.chords) {
    const double a = std::max(c.t_in, trace.t_eye);
    if (c.t_out - a > 1e-12) walked.push_back({c.cell, a, c.t_out});
  }
  REQUIRE(walked.size() == brute.size());
  double lw = 0, lb = 0;
  for (std::size_t i = 0; i < brute.size(); ++i) {
    CHECK(walked[i].cell == brute[i].cell);
    CHECK(std::fabs(walked[i].t_in - brute[i].t_in) <= 1e-12);
    CHECK(std::fabs(walked[i].t_out - brute[i].t_out) <= 1e-12);
    lw += walked[i].t_out - walked[i].t_in;
    lb += brute[i].t_out - brute[i].t_in;
  }
  CHECK(std::fabs(traced_length(trace) - lb) <= 1e-13 * (1.0 + lb));
  // Watertight: consecutive chords inside the mesh share their end points exactly.
  for (std::size_t i = 1; i < trace.chords.size(); ++i) CHECK(trace.chords[i].t_in >= trace.chords[i - 1].t_out);
}

}  // namespace

TEST_CASE("own traversal: whole rays through curved hexahedra equal every cell's 50-digit chord composited", "[celltraversal]") {
  // cells-twisted.vts (VTK 9.1: 4 x 3 x 2 twisted hexahedra) and cells-hex-41.msh (gmsh 4.8: two
  // recombined blocks of 27 hexahedra, the second twisted): random rays through the box, and rays
  // through interior vertices (shared by 8 hexahedra).
  const TransferFunctions tf = test::breakpoint_tf();  // breakpoints inside the fixtures' field range (0 .. ~1.3)
  const LinearCellIntegrator integrator(tf);
  for (const std::string f : {"cells-twisted.vts", "cells-hex-41.msh"}) {
    INFO(f);
    const CellMesh cells = read_cell_mesh_file(kDir + f);
    const std::vector<Vec3> vertices = shared_points(cells, 8);
    REQUIRE_FALSE(vertices.empty());
    const CellTraversal m(cells, f);
    std::mt19937_64 rng(29);
    double worst = 0.0;
    int rays = 0, nonempty = 0;
    for (int i = 0; i < 8; ++i) {
      const Vec3 target = i < 4 ? random_inside_box(m, rng) : vertices[static_cast<std::size_t>(i) * 7 % vertices.size()];
      const ViewRay ray = ray_through(m, target, rng);
      CellTrace trace;
      m.trace(ray, trace);
      CHECK(trace.failed_chords == 0);
      const std::vector<BruteChord> brute = brute_force(m, trace);
      check_chords_match(trace, brute);
      const CellRayResult got = m.integrate(trace, integrator, Rgb{0.0, 0.0, 0.0});
      REQUIRE(got.converged);
      Rgb e{}, d{};
      reference_ray(m, tf, trace, brute, e, d);
      for (std::size_t ch = 0; ch < 3; ++ch) {
        worst = std::max({worst, std::fabs(got.emission[ch] - e[ch]), std::fabs(got.optical_depth[ch] - d[ch])});
      }
      ++rays;
      nonempty += brute.empty() ? 0 : 1;
    }
    INFO("worst absolute difference " << worst);
    CHECK(worst <= 1e-13);
    CHECK(nonempty >= 6);  // the rays do cross the mesh
    CHECK(rays == 8);
  }
}

TEST_CASE("own traversal: rays through shared vertices and along shared edges lose and double nothing", "[celltraversal]") {
  // cells-odd.vtr (VTK: voxels on a non-uniform rectilinear grid, x in {0, 0.2, 0.7, 1},
  // y in {-0.5, 0.1, 0.4}, z in {0, 0.3, 1.1}): rays along grid lines (through edges shared by
  // 4 voxels and vertices shared by 8) cross the whole box: length exactly the box's.
  const CellTraversal m(read_cell_mesh_file(kDir + "cells-odd.vtr"), "odd");
  const double xs[] = {0.0, 0.2, 0.7, 1.0}, ys[] = {-0.5, 0.1, 0.4}, zs[] = {0.0, 0.3, 1.1};
  int rays = 0;
  for (double y : {ys[1], ys[2], 0.25})
    for (double z : {zs[1], 0.7, zs[0]}) {
      CellTrace trace;
      m.trace({Vec3(-2.0, y, z), Vec3(1, 0, 0)}, trace);
      INFO("y " << y << " z " << z);
      CHECK(std::fabs(traced_length(trace) - (xs[3] - xs[0])) <= 1e-14);
      ++rays;
    }
  // Diagonals through the interior vertex (0.2, 0.1, 0.3) and the vertex (0.7, 0.1, 0.3).
  CellTraversalStats stats;
  for (const Vec3& v : {Vec3(0.2, 0.1, 0.3), Vec3(0.7, 0.1, 0.3)}) {
    std::mt19937_64 rng(7);
    for (int i = 0; i < 20; ++i) {
      CellTrace trace;
      m.trace(ray_through(m, v, rng), trace, &stats);
      check_chords_match(trace, brute_force(m, trace));
      ++rays;
    }
  }
  CHECK(rays == 49);
  // Where no face neighbour continues a ray through the vertex, the next cell is found by the
  // star search (rule 2; its candidates filtered by their padded corner boxes, cell_traversal.cpp
  // next_cell), never by a re-entry: the box is convex, so each ray asks the first-hit structure
  // twice (its entry, and nothing after its exit).
  CHECK(stats.star_steps > 0);
  CHECK(stats.first_hit_queries == 2 * 40);
  // Curved faces: the twisted grid's interior vertices and edge midpoints.
  const CellMesh twisted = read_cell_mesh_file(kDir + "cells-twisted.vts");
  const std::vector<Vec3> vertices = shared_points(twisted, 4);
  const CellTraversal t(twisted, "twisted");
  std::mt19937_64 rng(11);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    CellTrace trace;
    t.trace(ray_through(t, vertices[i], rng), trace);
    CHECK(trace.failed_chords == 0);
    check_chords_match(trace, brute_force(t, trace));
  }
}

namespace {
// An n^3 block of hexahedra (VTK order) over [0, 1]^3 with its points moved by `map`; the scalar
// a smooth function of the unmoved point.
template <class Map>
CellMesh hex_block(int n, Map map) {
  CellMesh m;
  const auto id = [n](int i, int j, int k) { return static_cast<std::int32_t>(i + (n + 1) * (j + (n + 1) * k)); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const Vec3 x(static_cast<double>(i) / n, static_cast<double>(j) / n, static_cast<double>(k) / n);
        m.points.push_back(map(x));
        m.scalars.push_back(0.3 + 0.4 * x.x() * x.y() + 0.3 * x.z() * x.z());
      }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        for (const std::int32_t p : {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                                     id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)})
          m.connectivity.push_back(p);
        m.types.push_back(MeshCellType::hexahedron);
        m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
      }
  return m;
}
}  // namespace

TEST_CASE("own traversal: planar faces by their planes, affine cells by clipping, against every cell's own chord", "[celltraversal]") {
  // Sheared block: every cell a parallelepiped (affine, all faces planar: clipped). Tapered block
  // x -> x (1 + z / 2): all faces planar, no cell affine (planes + Newton classification).
  // Perturbed block: the sheared one with one interior point moved, so the 8 cells around it
  // are curved and their 12 faces through it bilinear, next to clipped cells. Rays through the
  // interior vertices (shared by 8 cells) and random rays: the walk's chords equal the brute force
  // (each cell's chord() on its own, bilinear patches throughout), and the chords join exactly.
  const int n = 3;
  const auto shear = [](const Vec3& x) { return Vec3(x.x() + 0.3 * x.y() + 0.2 * x.z(), x.y() + 0.1 * x.z(), 0.9 * x.z()); };
  CellMesh perturbed = hex_block(n, shear);
  const std::size_t moved = 1 + (n + 1) * (1 + (n + 1) * 1);  // point (1, 1, 1)
  perturbed.points[moved] += Vec3(0.03, -0.02, 0.025);
  struct Case {
    const char* name;
    CellMesh mesh;
    std::size_t clipped, planar;
  };
  const std::size_t faces = 3 * n * n * (n + 1);
  std::vector<Case> cases;
  cases.push_back({"sheared", hex_block(n, shear), 27, faces});
  cases.push_back({"tapered", hex_block(n, [](const Vec3& x) { return Vec3(x.x() * (1.0 + 0.5 * x.z()), x.y(), x.z()); }), 0, faces});
  cases.push_back({"perturbed", perturbed, 27 - 8, faces - 12});
  for (const Case& c : cases) {
    INFO(c.name);
    const CellTraversal m(c.mesh, c.name);
    CHECK(m.clipped_cell_count() == c.clipped);
    CHECK(m.planar_face_count() == c.planar);
    std::mt19937_64 rng(5);
    std::vector<Vec3> targets = shared_points(c.mesh, 8);
    for (int i = 0; i < 30; ++i) targets.push_back(random_inside_box(m, rng));
    for (const Vec3& v : targets) {
      CellTrace trace;
      m.trace(ray_through(m, v, rng), trace);
      CHECK(trace.failed_chords == 0);
      check_chords_match(trace, brute_force(m, trace));
    }
  }
}

TEST_CASE("own traversal: a field linear in space gives the split path's answer on meshes with planar boundaries", "[celltraversal]") {
  // f = 0.2 + 0.3 x - 0.2 y + 0.25 z at every point: each cell's isoparametric interpolant is
  // this same linear function (sum N_i = 1, sum N_i x_i = x), and so is each split tetrahedron's;
  // the boundaries are planar, so both integrate the same exact integral. gmsh's mixed hex/pyramid/
  // tet file, gmsh's prisms, VTK's rectilinear voxels.
  const TransferFunctions tf = test::breakpoint_tf();  // breakpoints inside the fixtures' field range (0 .. ~1.3)
  const LinearCellIntegrator integrator(tf);
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  for (const std::string f : {"cells-mixed-41.msh", "cells-prism-41.msh", "cells-odd.vtr"}) {
    INFO(f);
    CellMesh cells = read_cell_mesh_file(kDir + f);
    cells.cell_scalars.clear();
    cells.scalars.resize(cells.points.size());
    for (std::size_t p = 0; p < cells.points.size(); ++p) {
      const Vec3& x = cells.points[p];
      cells.scalars[p] = 0.2 + 0.3 * x.x() - 0.2 * x.y() + 0.25 * x.z();
    }
    const TetTraversal split(split_cells(cells), f);
    const CellTraversal own(cells, f);
    std::mt19937_64 rng(3);
    double worst = 0.0;
    int hit = 0;
    for (int i = 0; i < 40; ++i) {
      const ViewRay ray = ray_through(own, random_inside_box(own, rng), rng);
      CellTrace trace;
      own.trace(ray, trace);
      const CellRayResult a = own.integrate(trace, integrator, Rgb{0.1, 0.2, 0.3});
      REQUIRE(a.converged);
      const RayResult b = exact->integrate(mesh_ray(split, ray, Rgb{0.1, 0.2, 0.3}), nullptr);
      for (std::size_t ch = 0; ch < 3; ++ch) worst = std::max(worst, std::fabs(a.intensity[ch] - b.intensity[ch]));
      hit += trace.chords.empty() ? 0 : 1;
    }
    INFO("worst " << worst);
    CHECK(worst <= 1e-12);
    CHECK(hit >= 20);
  }
}

TEST_CASE("own traversal: a ray leaves a non-convex mesh and re-enters it", "[celltraversal]") {
  // A U of three unit hexahedra (cells (0,0), (0,1), (2,0), (2,1), (1,1) of a 3 x 2 grid; (1,0)
  // missing), the top row's far face bent (curved hexahedra). A ray along x at y = 0.5 crosses
  // the left arm, leaves at x = 1, re-enters at x = 2 and crosses the right arm.
  CellMesh m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i)
        m.points.push_back(Vec3(i, j, k + (k == 1 && j == 2 ? 0.3 * std::sin(i) : 0.0)));
  const auto id = [](int i, int j, int k) { return static_cast<std::int32_t>(i + 4 * (j + 3 * k)); };
  for (auto [i, j] : std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {1, 1}, {2, 1}, {2, 0}}) {
    for (auto p : {id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0), id(i, j, 1), id(i + 1, j, 1),
                   id(i + 1, j + 1, 1), id(i, j + 1, 1)})
      m.connectivity.push_back(p);
    m.types.push_back(MeshCellType::hexahedron);
    m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
  }
  for (const Vec3& p : m.points) m.scalars.push_back(0.3 + 0.2 * p.x() + 0.1 * p.y() * p.z());
  const CellTraversal t(m, "u");
  CHECK(t.boundary_face_count() == 5 * 6 - 2 * 4);
  const TransferFunctions tf = test::breakpoint_tf();  // breakpoints inside the fixtures' field range (0 .. ~1.3)
  const LinearCellIntegrator integrator(tf);
  for (double y : {0.5, 0.25, 1.0 /* along the shared faces' edge row */}) {
    INFO("y " << y);
    CellTraversalStats stats;
    CellTrace trace;
    t.trace({Vec3(-1, y, 0.5), Vec3(1, 0, 0)}, trace, &stats);
    CHECK(std::fabs(traced_length(trace) - (y < 1.0 ? 2.0 : 3.0)) <= 1e-14);
    if (y < 1.0) {
      CHECK(stats.first_hit_queries >= 3);  // entry, re-entry, and the final query that finds nothing
      REQUIRE(trace.chords.size() == 2);
      CHECK(trace.chords[1].t_in - trace.chords[0].t_out == Approx(1.0));
    }
    std::vector<BruteChord> brute;
    if (y < 1.0) {
      brute = brute_force(t, trace);
      check_chords_match(trace, brute);
    } else {
      // The ray lies in the faces shared by the two rows: both cells of each pair hold it (the
      // brute force lists both), the walk takes one; the field is continuous across the face,
      // so the reference integrates the walk's own chords.
      for (const auto& c : trace.chords) brute.push_back({c.cell, std::max(c.t_in, trace.t_eye), c.t_out});
      CHECK(trace.chords.size() == 3);
    }
    const CellRayResult got = t.integrate(trace, integrator, Rgb{0, 0, 0});
    REQUIRE(got.converged);
    Rgb e{}, d{};
    reference_ray(t, tf, trace, brute, e, d);
    for (std::size_t ch = 0; ch < 3; ++ch) {
      CHECK(std::fabs(got.emission[ch] - e[ch]) <= 1e-13);
      CHECK(std::fabs(got.optical_depth[ch] - d[ch]) <= 1e-13);
    }
  }
  // A ray that misses: no chords, the background only.
  CellTrace miss;
  t.trace({Vec3(-1, 0.5, 5), Vec3(1, 0, 0)}, miss);
  CHECK(miss.chords.empty());
  CHECK(t.integrate(miss, integrator, Rgb{0.25, 0.5, 1}).intensity[2] == 1.0);
}

TEST_CASE("own traversal: a face shared by three cells is refused naming them", "[celltraversal]") {
  CellMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 1, 1)};
  m.scalars.assign(m.points.size(), 0.5);
  for (auto apex : {3, 4, 5}) {
    for (auto p : {0, 1, 2, apex}) m.connectivity.push_back(p);
    m.types.push_back(MeshCellType::tetra);
    m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
  }
  CHECK_THROWS_WITH(CellTraversal(m, "three.vtu"), Catch::Contains("three.vtu: cells[2]: a face is shared by more than two cells"));
}

TEST_CASE("CLI: own mode by default for non-tet files, split on request, failed rays null and counted", "[celltraversal][cli]") {
  test::TempDir dir;
  const std::string tf = R"("transfer_function": {"density": [[0, 0.5], [1.3, 3]], "color": [[0, 1], [1.3, 0.2]]})";
  dir.write("hex.json", R"({"name": "hex", )" + tf + R"(, "mesh_file": ")" + kDir + R"(cells-hex-41.msh",
    "camera": {"position": [1.1, 0.3, 4], "look_at": [1.1, 0.5, 0.5], "fov_deg": 40, "width": 20, "height": 14}})");
  const auto own = test::run_cli(dir.path, "render hex.json -o own.pfm --stats own.json");
  REQUIRE(own.status == 0);
  CHECK(own.err.find("mode own: 54 hexahedron") != std::string::npos);
  const auto stats = nlohmann::json::parse(test::slurp(dir.path / "own.json"));
  CHECK(stats["method"] == "own");
  CHECK(stats["mesh"]["cells"]["mode"] == "own");
  CHECK(stats["failed_pixels"] == 0);
  CHECK(stats["cost"]["chords"].get<long>() > 100);
  // Its own image passes check --candidate-image (own mode); the split image is a different field.
  const auto same = test::run_cli(dir.path, "check hex.json --candidate-image own.pfm -o same.json -q");
  CHECK(same.status == 0);
  CHECK(nlohmann::json::parse(test::slurp(dir.path / "same.json"))["mode"] == "own");
  REQUIRE(test::run_cli(dir.path, "render hex.json --cells split -o split.pfm -q").status == 0);
  const auto differs = test::run_cli(dir.path, "check hex.json --candidate-image split.pfm -o differs.json -q");
  CHECK(differs.status == 1);
  const auto split_self = test::run_cli(dir.path, "check hex.json --cells split --candidate-image split.pfm -o s.json -q");
  CHECK(split_self.status == 0);
  // A bow-tie hexahedron (top face nodes 6 and 7 swapped): Newton cannot locate points in it,
  // those rays fail: null in eval (exit 1, counted), NaN pixels counted in render (exit 1).
  const nlohmann::json j = test::eval_bow_tie(dir, 24);
  const long failed = j["cases"][0]["failed"].get<long>();
  long nulls = 0;
  for (const auto& r : j["cases"][0]["rays"])
    if (r["intensity"].is_null()) {
      ++nulls;
      CHECK_FALSE(r["failure"].get<std::string>().empty());
    }
  CHECK(nulls == failed);
  const auto r = test::run_cli(dir.path, "render bow.json -o bow.pfm --stats bow-stats.json -q");
  CHECK(r.status == 1);
  CHECK(r.err.find("pixels failed") != std::string::npos);
  CHECK(nlohmann::json::parse(test::slurp(dir.path / "bow-stats.json"))["failed_pixels"].get<long>() == failed);
}
