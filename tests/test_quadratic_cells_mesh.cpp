// Meshes of quadratic cells as the real tools write them (tests/fixtures/quadratic/, by
// generate-quadratic.sh: gmsh 4.8 -order 2 on curved geometry -- a cylinder of tet10, a quarter
// annulus of hex20 and of hex27, a disc of prism15 and of prism18, a hexahedral block joined to
// tetrahedra by 13-node pyramids -- and VTK 9.1's blocks of hex20, wedge15, hex27, wedge18 and
// pyramid13 with displaced mid-edge (and face-centre) nodes; generate-pyramid13.sh), integrated in their own isoparametric interpolation by the own-cells traversal
// (mesh/cell_traversal.hpp). Tag [quadratic][mesh]. Oracles, none of them rayint's code:
//   - VTK's own interpolation (EvaluateLocation of vtkQuadraticTetra, vtkQuadraticHexahedron,
//     vtkQuadraticWedge, vtkTriQuadraticHexahedron, vtkBiQuadraticQuadraticWedge) of r at random parametric points of every file
//     VTK reads (quadratic-expected.json): reader node order and shape functions;
//   - gmsh's own legacy .vtk of the same mesh (VTK's node order): the gmsh permutations;
//   - the 50-digit reference (reference/cell_reference.hpp, ids 24-27, 29, 32) per chord;
//   - for straight-edged tet10, the tetrahedral path's exact quadratic (mesh/quadratic_tets.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/quadratic_isoparametric.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "rayint/studies/own_cells_eval.hpp"

using namespace rayint;
namespace fs = std::filesystem;

namespace {

const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/quadratic/";

struct Tolerances {
  // Position and value against VTK's at VTK's parametric point: VTK's formulas and ours (the
  // Vandermonde construction, quadratic_cells.hpp: <= 1.8e-15 per weight) sum 10-20 terms of
  // O(1) values; 1e-13.
  static constexpr double vtk_abs = 1e-13;
  // The double path against the 50-digit reference per chord, relative per channel (the linear
  // cells' target, test_linear_cells.cpp).
  static constexpr double reference_rel = 1e-13;
  // Straight-edged tet10: the own path (polynomial, Chebyshev + Gauss-Kronrod to 1e-14) against
  // the tetrahedral path's exact quadratic; issue 29's "~1e-14".
  static constexpr double straight_tet10_rel = 1e-13;
  // Chord ends computed from different faces through one edge or vertex differ by rounding.
  static constexpr double tiling_abs = 1e-12;
};

// Breakpoints inside the range of r (about -1.5 to 1.5).
TransferFunctions steep_tf() {
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{-1.0, 0.2, 0.7, 1.2}, {0.1, 1.5, 0.3, 2.0}},
                PiecewiseLinear{{0.0, 0.5, 1.0}, {0.4, 0.2, 1.2}}, PiecewiseLinear{{-0.5, 0.9}, {1.0, 0.5}}};
  tf.color = {PiecewiseLinear{{0.0, 1.0}, {0.2, 1.0}}, PiecewiseLinear{{-0.2, 0.4, 1.4}, {1.0, 0.1, 0.8}},
              PiecewiseLinear{{0.3}, {0.6}}};
  return tf;
}

std::size_t kept_index(const CellMesh& mesh, long long file_cell) {
  for (std::size_t c = 0; c < mesh.info.cell_ids.size(); ++c)
    if (mesh.info.cell_ids[c] == file_cell) return c;
  FAIL("cell " << file_cell << " not kept");
  return 0;
}

// Rays from outside the mesh's box through random points of it.
std::vector<ViewRay> random_rays(const CellTraversal& m, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  const Vec3 lo = m.box_min(), hi = m.box_max();
  const double diag = (hi - lo).norm();
  std::vector<ViewRay> rays;
  while (static_cast<int>(rays.size()) < n) {
    const Vec3 target = lo + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo);
    Vec3 dir(w(rng), w(rng), w(rng));
    if (dir.norm() < 0.2) continue;
    dir.normalize();
    rays.push_back({target - 2.0 * diag * dir, dir});
  }
  return rays;
}

CellReferenceInput reference_input(const QuadraticCell& cell, const CellTrace& trace, double t_near, double t_far) {
  return cell_reference_input(cell, trace.origin, trace.direction, t_near, t_far);
}

const char* kMeshes[] = {"cylinder-tet10-41.msh",  "cylinder-tet10-22.msh",  "cylinder-tet10-gmsh.vtk",
                         "annulus-hex20-41.msh",   "annulus-hex20-22.msh",   "annulus-hex20-gmsh.vtk",
                         "disc-prism15-41.msh",    "disc-prism15-gmsh.vtk",  "block-hex20.vtu",
                         "block-wedge15.vtk",      "annulus-hex27-41.msh",   "annulus-hex27-22.msh",
                         "annulus-hex27-gmsh.vtk", "disc-prism18-41.msh",    "disc-prism18-22.msh",
                         "disc-prism18-gmsh.vtk",  "block-hex27.vtu",        "block-hex27.vtk",
                         "block-wedge18.vtk",      "block-wedge18.vtu",      "transition-pyramid13-41.msh",
                         "transition-pyramid13-22.msh", "block-pyramid13.vtu", "block-pyramid13.vtk"};

}  // namespace

TEST_CASE("quadratic cells: every reader's node order and interpolation equal VTK's at random points", "[quadratic][mesh][readers]") {
  // quadratic-expected.json (generate_quadratic.py) and pyramid13-expected.json (generate_pyramid13.py:
  // vtkQuadraticPyramid on VTK's own pyramid13 blocks, .vtu and legacy .vtk).
  std::ifstream in(kDir + "quadratic-expected.json"), in13(kDir + "pyramid13-expected.json");
  REQUIRE(in.good());
  REQUIRE(in13.good());
  nlohmann::json j = nlohmann::json::parse(in);
  int pyramid_samples = 0;
  const nlohmann::json j13 = nlohmann::json::parse(in13);
  for (const auto& s : j13["samples"]) {
    j["samples"].push_back(s);
    ++pyramid_samples;
  }
  CHECK(pyramid_samples == 80);
  std::map<std::string, CellMesh> meshes;
  double worst_x = 0.0, worst_r = 0.0, worst_pyramid = 0.0;
  int n = 0;
  for (const auto& s : j["samples"]) {
    const std::string file = s["file"];
    if (!meshes.count(file)) meshes.emplace(file, read_cell_mesh_file(kDir + file, {"r"}));
    const CellMesh& mesh = meshes.at(file);
    const std::size_t c = kept_index(mesh, s["cell"].get<long long>());
    CHECK(static_cast<int>(mesh.types[c]) == s["vtk_type"].get<int>());
    QuadraticCellType type;
    REQUIRE(quadratic_cell_type_from_vtk(static_cast<int>(mesh.types[c]), type));
    const Vec3 p(s["p"][0].get<double>(), s["p"][1].get<double>(), s["p"][2].get<double>());
    const Vec3 x(s["x"][0].get<double>(), s["x"][1].get<double>(), s["x"][2].get<double>());
    double N[kMaxQuadraticNodes];
    quadratic_shape_functions(type, p, N);
    Vec3 xs = Vec3::Zero();
    double r = 0.0;
    for (std::size_t k = 0; k < mesh.nodes_of(c); ++k) {
      const auto i = static_cast<std::size_t>(mesh.cell(c)[k]);
      xs += N[k] * mesh.points[i];
      r += N[k] * mesh.scalars[i];
    }
    worst_x = std::max(worst_x, (xs - x).cwiseAbs().maxCoeff());
    worst_r = std::max(worst_r, std::abs(r - s["r"].get<double>()));
    if (type == QuadraticCellType::pyramid)
      worst_pyramid = std::max({worst_pyramid, (xs - x).cwiseAbs().maxCoeff(), std::abs(r - s["r"].get<double>())});
    ++n;
  }
  CHECK(n >= 520);
  CHECK(worst_x <= Tolerances::vtk_abs);
  CHECK(worst_r <= Tolerances::vtk_abs);
  WARN("quadratic cells vs VTK, " << n << " points of " << meshes.size() << " files: worst |x - VTK| " << worst_x
                                  << ", |r - VTK| " << worst_r << "; the " << pyramid_samples
                                  << " quadratic pyramid points: worst of both " << worst_pyramid);
}

TEST_CASE("quadratic cells: gmsh's .msh read through the cell table equals gmsh's own VTK-order .vtk", "[quadratic][mesh][readers]") {
  const std::pair<const char*, const char*> pairs[] = {{"cylinder-tet10-41.msh", "cylinder-tet10-gmsh.vtk"},
                                                       {"cylinder-tet10-22.msh", "cylinder-tet10-gmsh.vtk"},
                                                       {"annulus-hex20-41.msh", "annulus-hex20-gmsh.vtk"},
                                                       {"annulus-hex20-22.msh", "annulus-hex20-gmsh.vtk"},
                                                       {"disc-prism15-41.msh", "disc-prism15-gmsh.vtk"},
                                                       {"annulus-hex27-41.msh", "annulus-hex27-gmsh.vtk"},
                                                       {"annulus-hex27-22.msh", "annulus-hex27-gmsh.vtk"},
                                                       {"disc-prism18-41.msh", "disc-prism18-gmsh.vtk"},
                                                       {"disc-prism18-22.msh", "disc-prism18-gmsh.vtk"}};
  for (const auto& [msh, vtk] : pairs) {
    INFO(msh << " vs " << vtk);
    const CellMesh a = read_cell_mesh_file(kDir + msh, {"r"}), b = read_cell_mesh_file(kDir + vtk, {"r"});
    REQUIRE(a.cell_count() == b.cell_count());
    for (std::size_t c = 0; c < a.cell_count(); ++c) {
      REQUIRE(a.types[c] == b.types[c]);
      REQUIRE(is_quadratic(a.types[c]));
      for (std::size_t k = 0; k < a.nodes_of(c); ++k) {
        const auto pa = static_cast<std::size_t>(a.cell(c)[k]), pb = static_cast<std::size_t>(b.cell(c)[k]);
        CHECK((a.points[pa] - b.points[pb]).cwiseAbs().maxCoeff() <= 1e-15);  // gmsh prints 16 digits in both
        CHECK(a.scalars[pa] == Approx(b.scalars[pb]).margin(1e-15));
      }
    }
  }
}

TEST_CASE("quadratic cells: gmsh's 27-node hexahedra and 18-node prisms are read as VTK types 29 and 32, face nodes at their faces", "[quadratic][mesh][readers]") {
  // Independent of VTK: in gmsh's curved meshes every face-centre node lies closest to the mean
  // of its own face's corners among the cell's face-centre nodes (VTK's faces: vtkTriQuadraticHexahedron.h,
  // vtkBiQuadraticQuadraticWedge.h), and the hexahedron's last node closest to the mean of all corners.
  struct Case {
    const char* file;
    MeshCellType type;
    int first;  // first face-centre node
    std::vector<std::vector<int>> faces;
  };
  const Case cases[] = {
      {"annulus-hex27-41.msh", MeshCellType::triquadratic_hexahedron, 20,
       {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}}},
      {"annulus-hex27-22.msh", MeshCellType::triquadratic_hexahedron, 20,
       {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}}},
      {"disc-prism18-41.msh", MeshCellType::biquadratic_quadratic_wedge, 15, {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}},
      {"disc-prism18-22.msh", MeshCellType::biquadratic_quadratic_wedge, 15, {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}}};
  for (const Case& k : cases) {
    INFO(k.file);
    const CellMesh mesh = read_cell_mesh_file(kDir + k.file, {"r"});
    REQUIRE(mesh.cell_count() > 0);
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      REQUIRE(mesh.types[c] == k.type);
      const auto at = [&](int local) { return mesh.points[static_cast<std::size_t>(mesh.cell(c)[local])]; };
      for (std::size_t f = 0; f < k.faces.size(); ++f) {
        Vec3 mean = Vec3::Zero();
        for (int i : k.faces[f]) mean += at(i);
        mean /= static_cast<double>(k.faces[f].size());
        int nearest = -1;
        double best = 1e300;
        for (std::size_t g = 0; g < k.faces.size(); ++g) {
          const double d = (at(k.first + static_cast<int>(g)) - mean).norm();
          if (d < best) best = d, nearest = static_cast<int>(g);
        }
        CHECK(nearest == static_cast<int>(f));
      }
    }
  }
}

TEST_CASE("quadratic cells: mesh rays against the 50-digit reference chord by chord, chords tiling the ray", "[quadratic][mesh][reference]") {
  const TransferFunctions tf = steep_tf();
  const LinearCellIntegrator integrator(tf);
  for (const char* file : kMeshes) {
    INFO(file);
    const CellTraversal m(read_cell_mesh_file(kDir + file, {"r"}), file);
    CellTrace trace;
    CellTraversalStats stats;
    double worst = 0.0;
    int checked = 0, chords = 0;
    for (const ViewRay& ray : random_rays(m, 12, 41)) {
      m.trace(ray, trace, &stats);
      REQUIRE(trace.failed_chords == 0);
      for (std::size_t k = 0; k + 1 < trace.chords.size(); ++k)
        CHECK(trace.chords[k].t_out <= trace.chords[k + 1].t_in);  // t never decreases
      const CellRayResult r = m.integrate(trace, integrator, Rgb{0.0, 0.0, 0.0});
      REQUIRE(r.converged);
      chords += static_cast<int>(trace.chords.size());
      // Every 4th chord against the reference (it costs ~0.1 s a chord).
      for (std::size_t k = 0; k < trace.chords.size(); k += 4) {
        const CellChordOnRay& ch = trace.chords[k];
        const QuadraticCell* q = m.quadratic_cell(static_cast<std::size_t>(ch.cell));
        REQUIRE(q != nullptr);
        const ViewRay local{trace.origin, trace.direction};
        const CellPieceIntegral d = integrator.integrate(*q, local, ch.t_in, ch.t_out);
        REQUIRE(d.converged);
        const CellReference ref = reference_cell_chord(tf, reference_input(*q, trace, ch.t_in, ch.t_out));
        for (std::size_t c = 0; c < kChannels; ++c) {
          const double e = std::abs(d.emission[c] - ref.emission[c]), o = std::abs(d.optical_depth[c] - ref.optical_depth[c]);
          const double re = ref.emission[c] > 0 ? e / ref.emission[c] : e, ro = ref.optical_depth[c] > 0 ? o / ref.optical_depth[c] : o;
          worst = std::max({worst, re, ro});
          INFO("cell " << ch.cell << " path " << cell_path_name(d.path) << " errors " << re << " " << ro);
          CHECK(re <= Tolerances::reference_rel);
          CHECK(ro <= Tolerances::reference_rel);
        }
        ++checked;
      }
    }
    CHECK(chords > 12);
    CHECK(stats.budget_exhausted == 0);
    WARN(file << ": " << m.cell_count() << " cells, " << chords << " chords on 12 rays, " << checked
              << " against the 50-digit reference: worst relative error " << worst);
  }
}

TEST_CASE("quadratic cells: rays through shared curved faces, edges and vertices neither drop nor double a piece", "[quadratic][mesh]") {
  // The chords of a ray must tile the inside of the mesh's closed boundary: the boundary patches'
  // hits, sorted, alternate entry and exit (parity); the chords' union must be those intervals.
  // Rays aim at the mesh's own nodes (vertices of 2-8 cells, mid-edge nodes of shared edges) and
  // at points of shared faces.
  for (const char* file : {"block-hex20.vtu", "block-wedge15.vtk", "annulus-hex20-41.msh", "disc-prism15-41.msh",
                           "cylinder-tet10-41.msh", "annulus-hex27-41.msh", "disc-prism18-41.msh", "block-hex27.vtu",
                           "block-wedge18.vtk", "block-pyramid13.vtu", "transition-pyramid13-41.msh"}) {
    INFO(file);
    const CellTraversal m(read_cell_mesh_file(kDir + file, {"r"}), file);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> w(-1.0, 1.0);
    std::uniform_int_distribution<std::size_t> pick(0, m.mesh().points.size() - 1);
    const double diag = (m.box_max() - m.box_min()).norm();
    int rays = 0;
    for (int k = 0; k < 80; ++k) {
      Vec3 target = m.mesh().points[pick(rng)];
      if (k % 4 == 3) {  // a point inside a face shared by two cells: the mean of a face's nodes
        const std::size_t c = pick(rng) % m.cell_count();
        target = 0.5 * (m.mesh().points[static_cast<std::size_t>(m.mesh().cell(c)[0])] +
                        m.mesh().points[static_cast<std::size_t>(m.mesh().cell(c)[1])]);
      }
      Vec3 dir(w(rng), w(rng), w(rng));
      dir.normalize();
      const ViewRay ray{target - 2.0 * diag * dir, dir};
      CellTrace trace;
      m.trace(ray, trace);
      REQUIRE(trace.failed_chords == 0);
      // Boundary patch hits in the trace's parameters.
      const ViewRay local{trace.origin, trace.direction};
      std::vector<double> hits;
      for (std::size_t b = 0; b < m.boundary_face_count(); ++b) {
        const auto& f = m.boundary_face(b);
        PatchNodes nodes{};
        for (int i = 0; i < f.count; ++i) {
          nodes[static_cast<std::size_t>(i)] = m.mesh().points[static_cast<std::size_t>(f.points[static_cast<std::size_t>(i)])];
          nodes[static_cast<std::size_t>(f.count + i)] = m.mesh().points[static_cast<std::size_t>(f.mids[static_cast<std::size_t>(i)])];
        }
        if (f.centre >= 0) nodes[static_cast<std::size_t>(2 * f.count)] = m.mesh().points[static_cast<std::size_t>(f.centre)];
        for (const PatchHit& h : intersect_quadratic_face(nodes, f.count, f.centre >= 0, local)) hits.push_back(h.t);
      }
      std::sort(hits.begin(), hits.end());
      // Hits of one crossing found twice (on a boundary edge or vertex: two patches) merge.
      std::vector<double> crossings;
      for (double t : hits)
        if (crossings.empty() || t - crossings.back() > Tolerances::tiling_abs * diag) crossings.push_back(t);
      if (crossings.size() % 2 != 0) continue;  // a tangency or a grazing vertex: parity undefined
      std::vector<std::pair<double, double>> pieces;
      for (const CellChordOnRay& c : trace.chords) {
        if (!pieces.empty() && std::abs(c.t_in - pieces.back().second) <= Tolerances::tiling_abs * diag)
          pieces.back().second = c.t_out;
        else
          pieces.emplace_back(c.t_in, c.t_out);
      }
      // Empty-length intervals (grazing an edge or vertex of the boundary) hold no piece.
      std::vector<std::pair<double, double>> inside;
      for (std::size_t i = 0; i + 1 < crossings.size(); i += 2)
        if (crossings[i + 1] - crossings[i] > Tolerances::tiling_abs * diag) inside.emplace_back(crossings[i], crossings[i + 1]);
      INFO("ray " << k << " target " << target.transpose() << " chords " << trace.chords.size());
      REQUIRE(pieces.size() == inside.size());
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        CHECK(std::abs(pieces[i].first - inside[i].first) <= Tolerances::tiling_abs * diag);
        CHECK(std::abs(pieces[i].second - inside[i].second) <= Tolerances::tiling_abs * diag);
      }
      ++rays;
    }
    // Rays aimed at boundary nodes may graze the boundary (odd parity, skipped above): at least
    // half of the 80 are checked (measured: 57 to 78 per file).
    CHECK(rays >= 40);
    WARN(file << ": " << rays << " of 80 rays through nodes and shared faces checked, chords tile the inside");
  }
}

TEST_CASE("quadratic cells: straight-edged tet10 in the own path equal the tetrahedral path's exact quadratic", "[quadratic][mesh][tet10]") {
  const TransferFunctions tf = steep_tf();
  const std::string file = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/tet10-22.msh";
  TetMesh tets = read_mesh_file(file, {"r"});
  REQUIRE(check_tet10_edges(tets).straight());
  const CellTraversal own(cell_mesh_of(TetMesh(tets)), file);
  repair_tet_mesh(tets, file);
  const TetTraversal tetra(std::move(tets), file);
  const QuadraticTraceIntegrator exact(tf);
  const LinearCellIntegrator integrator(tf);
  double worst = 0.0;
  for (const ViewRay& ray : random_rays(own, 40, 9)) {
    CellTrace ct;
    own.trace(ray, ct);
    const CellRayResult a = own.integrate(ct, integrator, Rgb{0.0, 0.0, 0.0});
    REQUIRE(a.converged);
    RayTrace tt;
    tetra.trace(ray, tt);
    const RayResult b = exact.integrate(tt, Rgb{0.0, 0.0, 0.0});
    for (std::size_t c = 0; c < kChannels; ++c) {
      const double scale = std::max(std::abs(b.intensity[c]), 1e-300);
      worst = std::max(worst, std::abs(a.intensity[c] - b.intensity[c]) / scale);
      CHECK(std::abs(a.intensity[c] - b.intensity[c]) <= Tolerances::straight_tet10_rel * scale);
      CHECK(std::exp(-a.optical_depth[c]) == Approx(b.transmittance[c]).epsilon(Tolerances::straight_tet10_rel));
    }
  }
  WARN("straight tet10, own path vs quadratic_tets' exact path, 40 rays: worst relative difference " << worst);
}

TEST_CASE("quadratic cells: a folded cell in a file is refused naming the file and the cell", "[quadratic][mesh]") {
  const std::string file = kDir + "block-hex20-folded.vtu";
  std::string msg;
  try {
    const CellTraversal m(read_cell_mesh_file(file, {"r"}), file);
  } catch (const InputError& e) {
    msg = e.what();
  }
  CHECK(msg.rfind(file + ": cells[1]: quadratic hexahedron: the isoparametric map is not one-to-one", 0) == 0);
  CHECK(msg.find('\n') == std::string::npos);
}

TEST_CASE("CLI: render integrates curved tet10, hex20, prism15, hex27, prism18 and pyramid13 files, --cells split refuses them", "[quadratic][mesh][cli]") {
  rayint::test::TempDir dir;
  const std::string tf = R"("transfer_function": {"density": [[-1, 0.2], [1.5, 2]], "color": [[-1, 0.1], [1.5, 1]]})";
  for (const char* file : {"cylinder-tet10-41.msh", "annulus-hex20-41.msh", "disc-prism15-41.msh", "block-hex20.vtu",
                           "annulus-hex27-41.msh", "disc-prism18-41.msh", "block-hex27.vtu", "block-wedge18.vtk",
                           "block-pyramid13.vtu", "transition-pyramid13-41.msh", "transition-pyramid13-22.msh"}) {
    INFO(file);
    dir.write("s.json", R"({"name": "s", )" + tf + R"(, "mesh_file": ")" + kDir + file +
                            R"(", "scalar_field": "r", "camera": {"position": [3, 2, 4], "look_at": [0.5, 0.5, 0.3], "fov_deg": 40, "width": 8, "height": 8}})");
    const auto r = rayint::test::run_cli(dir.path, "render s.json -o s.png");
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(fs::exists(dir.path / "s.png"));
    fs::remove(dir.path / "s.png");
    const auto split = rayint::test::run_cli(dir.path, "render s.json --cells split -o s.png");
    CHECK(split.status == 2);
    CHECK(split.err.find(std::string(kDir) + file + ": cells[") != std::string::npos);
    CHECK(split.err.find("--cells split") != std::string::npos);
    CHECK(split.err.find('\n') == split.err.size() - 1);
    CHECK_FALSE(fs::exists(dir.path / "s.png"));
    // eval: the own path against the 50-digit reference of the same cells (all their nodes).
    dir.write("e.json", R"({"name": "e", )" + tf + R"(, "mesh_file": ")" + kDir + file +
                            R"(", "scalar_field": "r", "rays": [{"origin": [3, 2, 4], "direction": [-0.55, -0.35, -0.76]},
                                {"origin": [-2, 0.4, 0.3], "direction": [1, 0.05, 0.02]}]})");
    const auto e = rayint::test::run_cli(dir.path, "eval e.json --no-timing -q -o e.out.json");
    INFO(e.err);
    REQUIRE(e.status == 0);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream((dir.path / "e.out.json").string()));
    const auto& c = j["cases"][0];
    CHECK(c["mode"] == "own");
    CHECK(c["failed"] == 0);
    for (const auto& ray : c["rays"]) CHECK(ray["abs_error"].is_number());  // referenced, not a default 0
    // Intensities O(0.1-1) composited from chords each within ~1e-14 relative of the reference.
    CHECK(c["max_abs_error"].get<double>() <= 1e-12);
  }
}

TEST_CASE("quadratic pyramid: gmsh's 13-node pyramids are read as VTK type 27, every mid-edge node at its own edge", "[quadratic][mesh][readers][pyramid]") {
  // Independent of VTK and of rayint's table: in gmsh's mesh each pyramid's mid-edge node k (VTK
  // order, vtkQuadraticPyramid.h's edges) lies nearest the midpoint of its own edge among the
  // cell's 8 edges (the pyramids of the transition sit on the flat interface, their edges straight:
  // measured at the midpoint to 1e-15). The same cells from .msh 4.1 and 2.2.
  const int edges[8][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
  std::vector<std::vector<Vec3>> seen;
  for (const char* file : {"transition-pyramid13-41.msh", "transition-pyramid13-22.msh"}) {
    INFO(file);
    const CellMesh mesh = read_cell_mesh_file(kDir + file, {"r"});
    int pyramids = 0;
    double worst = 0.0;
    std::vector<Vec3> nodes;
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      if (mesh.types[c] != MeshCellType::quadratic_pyramid) continue;
      ++pyramids;
      REQUIRE(mesh.nodes_of(c) == 13);
      const auto at = [&](int local) { return mesh.points[static_cast<std::size_t>(mesh.cell(c)[local])]; };
      for (int k = 0; k < 13; ++k) nodes.push_back(at(k));
      for (int k = 0; k < 8; ++k) {
        int nearest = -1;
        double best = 1e300;
        for (int e = 0; e < 8; ++e) {
          const double d = (at(5 + k) - 0.5 * (at(edges[e][0]) + at(edges[e][1]))).norm();
          if (d < best) best = d, nearest = e;
        }
        CHECK(nearest == k);
        worst = std::max(worst, (at(5 + k) - 0.5 * (at(edges[k][0]) + at(edges[k][1]))).norm());
      }
    }
    CHECK(pyramids == 9);
    CHECK(worst <= 1e-12);
    seen.push_back(nodes);
  }
  REQUIRE(seen.size() == 2);
  REQUIRE(seen[0].size() == seen[1].size());
  for (std::size_t i = 0; i < seen[0].size(); ++i) CHECK((seen[0][i] - seen[1][i]).cwiseAbs().maxCoeff() <= 1e-15);
}
