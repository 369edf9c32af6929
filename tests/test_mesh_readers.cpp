// The readers on files the real tools wrote (tests/fixtures/readers/, by generate.sh: gmsh 4.8,
// TetGen 1.6, VTK 9.1's writers, meshio), tag [mesh][readers]. The oracle of every file is what
// VTK's own reader (for .msh: meshio) read from it, dumped by generate.py into expected.json:
// points bit for bit, cells by type, arrays. Integrals are checked against an independent
// reference: the analytic chord through the cube [-1,1]^3 of the linear field
// s = 0.5 + 0.3x - 0.2y + 0.4z (one segment), or for the cell field c (1 for x < 0, 2 for x > 0)
// the two constant segments either side of x = 0, integrated by the exact closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/gmsh_reader.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/tetgen_reader.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "tolerances.hpp"
#include "input_text.hpp"
#include "mesh_case_fixtures.hpp"

using namespace rayint;
namespace fs = std::filesystem;

namespace {

const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/";

const nlohmann::json& oracle() {
  static const nlohmann::json j = nlohmann::json::parse(rayint::test::slurp(fs::path(kDir) / "expected.json"));
  return j;
}

// Any mesh file by extension, as a mesh case reads it.
TetMesh read_any(const std::string& file, const ScalarChoice& scalar = {}) {
  const std::string path = kDir + file;
  const std::string ext = fs::path(file).extension().string();
  if (ext == ".msh") return read_gmsh(path, scalar);
  if (ext == ".vtk") return read_vtk_legacy(path, scalar);
  if (ext == ".vtu") return read_vtu(path, scalar);
  if (ext == ".pvtu") return read_pvtu(path, scalar);
  if (ext == ".ele") return read_tetgen(path, scalar.name);
  FAIL("no reader for " << file);
  return {};
}

using rayint::test::linear_field;

TransferFunctions test_tf() {
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{-0.5, 0.4, 1.5}, {0.2, 1.6, 0.4}},
                PiecewiseLinear{{-0.5, 1.5, 2.5}, {0.9, 0.3, 0.5}}, PiecewiseLinear{{0.0}, {0.7}}};
  tf.color = {PiecewiseLinear{{-0.5, 2.5}, {0.1, 0.9}}, PiecewiseLinear{{0.0, 2.0}, {0.8, 0.2}},
              PiecewiseLinear{{0.0}, {0.5}}};
  return tf;
}

// Analytic rays: the linear field (one segment: test::analytic_linear_ray), or the cell field c
// (constant pieces split at x = 0).
Ray analytic_cells(const ViewRay& r, const Rgb& bg) {
  const Vec3 d = r.direction.normalized();
  const auto [t0, t1] = rayint::test::cube_chord(r);
  Ray ray;
  ray.background = bg;
  if (!(t1 > t0)) return ray;
  const auto c = [&](double t) { return (r.origin + t * d).x() < 0.0 ? 1.0 : 2.0; };
  double tx = d.x() != 0.0 ? -r.origin.x() / d.x() : -1.0;
  if (tx > t0 && tx < t1) {  // far piece first
    ray.segments.push_back({t1 - tx, c(0.5 * (tx + t1)), c(0.5 * (tx + t1))});
    ray.segments.push_back({tx - t0, c(0.5 * (t0 + tx)), c(0.5 * (t0 + tx))});
  } else {
    ray.segments.push_back({t1 - t0, c(0.5 * (t0 + t1)), c(0.5 * (t0 + t1))});
  }
  return ray;
}

// Largest relative intensity difference from the analytic ray over 500 rays through [-0.9,0.9]^3.
double max_rel_vs(const TetMesh& as_read, const std::string& name, Ray (*analytic)(const ViewRay&, const Rgb&)) {
  TetMesh mesh = as_read;
  repair_tet_mesh(mesh, name);
  const TetTraversal m(mesh, name);
  const TransferFunctions tf = test_tf();
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  std::mt19937_64 rng(27);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 o = 4.0 * Vec3(g(rng), g(rng), g(rng)).normalized();
    const ViewRay r{o, Vec3(u(rng), u(rng), u(rng)) - o};
    const Rgb bg{0.1, 0.2, 0.3};
    const RayResult got = exact->integrate(mesh_ray(m, r, bg), nullptr);
    const RayResult want = exact->integrate(analytic(r, bg), nullptr);
    for (int c = 0; c < kChannels; ++c)
      worst = std::max(worst, std::fabs(got.intensity[c] - want.intensity[c]) / std::fabs(want.intensity[c]));
  }
  return worst;
}

void check_points(const TetMesh& m, const nlohmann::json& want) {
  REQUIRE(m.points.size() == want.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < m.points.size(); ++i)
    for (int k = 0; k < 3; ++k) differ += m.points[i][k] != want[i][static_cast<std::size_t>(k)].get<double>();
  CHECK(differ == 0);
}

// The oracle's count of cells of VTK type `vtk` (meshio names for .msh files).
long oracle_count(const nlohmann::json& o, int vtk) {
  const auto& c = o["cell_type_counts"];
  const std::string key = std::to_string(vtk);
  if (c.contains(key)) return c[key].get<long>();
  static const std::map<int, std::string> meshio = {{1, "vertex"}, {3, "line"}, {5, "triangle"}, {10, "tetra"}};
  const auto it = meshio.find(vtk);
  return it != meshio.end() && c.contains(it->second) ? c[it->second].get<long>() : 0;
}

}  // namespace

TEST_CASE("boundary cells beside the tets are skipped and counted alike by every reader", "[mesh][readers]") {
  for (const std::string file : {"box-22.msh", "box-41.msh", "box-gmsh.vtk", "boundary.vtu", "boundary-vtk.vtu",
                                 "boundary-ascii.vtk"}) {
    INFO(file);
    const nlohmann::json& o = oracle()[file];
    const TetMesh m = read_any(file);
    CHECK(static_cast<long>(m.tets.size()) == oracle_count(o, kVtkTetra));
    CHECK(m.info.skipped_by_type.at("vertex") == oracle_count(o, kVtkVertex));
    CHECK(m.info.skipped_by_type.at("line") == oracle_count(o, kVtkLine));
    CHECK(m.info.skipped_by_type.at("triangle") == oracle_count(o, kVtkTriangle));
    CHECK(m.info.skipped_cells == oracle_count(o, kVtkVertex) + oracle_count(o, kVtkLine) + oracle_count(o, kVtkTriangle));
    CHECK(m.info.skipped_cells == 200);  // gmsh's 8 corners, 36 edge segments, 156 face triangles
    if (o["points"].is_array()) check_points(m, o["points"]);
    // The tags gmsh and meshio write are listed, never taken.
    CHECK(m.info.scalar == "s");
    for (const MeshArrayInfo& a : m.info.arrays)
      if (a.association == "cell") CHECK(a.marker);  // gmsh:physical, gmsh:geometrical, CellEntityIds
    const double rel = max_rel_vs(m, file, rayint::test::analytic_linear_ray);
    WARN(file << ": " << m.tets.size() << " tets, " << m.info.skipped_cells
              << " boundary cells skipped; max rel |I - I_analytic| over 500 rays = " << rel);
    // The ASCII files hold the coordinates and the field rounded as their writers print them
    // (VTK 9.1's legacy writer: doubles with 11 significant digits, "%.11lg"; meshio's ASCII .vtu
    // likewise), and rayint reads exactly what VTK reads (points above, bit for bit): the mesh is
    // then ~1e-12 away from gmsh's, and the integral (measured: 8.5e-13, 1.0e-11) with it.
    const bool ascii_copy = file == "boundary.vtu" || file == "boundary-ascii.vtk";
    CHECK(rel <= (ascii_copy ? 1e-10 : test::Tolerances::exact_rel));
  }
}

TEST_CASE("LZ4 and LZMA compressed .vtu with UInt32 and UInt64 headers read to VTK's points, cells and field", "[mesh][readers][vtkxml]") {
  for (const std::string file : {"lz4.vtu", "lzma.vtu", "lzma-h64.vtu"}) {
    INFO(file);
    const nlohmann::json& o = oracle()[file];
    const TetMesh m = read_any(file);
    check_points(m, o["points"]);
    REQUIRE(m.tets.size() == o["tets"].size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < m.tets.size(); ++i)
      for (std::size_t k = 0; k < 4; ++k) differ += m.tets[i][k] != o["tets"][i][k].get<std::int64_t>();
    CHECK(differ == 0);
    const auto& s = o["point_arrays"]["s"]["values"];
    REQUIRE(m.scalars.size() == s.size());
    for (std::size_t i = 0; i < s.size(); ++i) differ += m.scalars[i] != s[i].get<double>();
    CHECK(differ == 0);
    CHECK(max_rel_vs(m, file, rayint::test::analytic_linear_ray) <= test::Tolerances::exact_rel);
  }
}

TEST_CASE("a .pvtu with ghost cells: pieces joined, duplicated cells dropped and counted once", "[mesh][readers][vtkxml]") {
  const nlohmann::json& o = oracle()["ghost.pvtu"];
  const auto& ghost = o["cell_arrays"]["vtkGhostType"]["values"];
  long duplicates = 0;
  for (const auto& g : ghost) duplicates += (static_cast<unsigned>(g.get<double>()) & 1U) != 0;
  const TetMesh m = read_any("ghost.pvtu");
  CHECK(m.info.ghost_cells == duplicates);
  CHECK(duplicates > 0);
  CHECK(static_cast<long>(m.tets.size()) == oracle_count(o, kVtkTetra) - duplicates);
  const TetMesh whole = read_any("several.vtu");
  CHECK(m.tets.size() == whole.tets.size());
  CHECK(m.points.size() == whole.points.size());  // the points repeated on the cut are merged
  CHECK(m.info.merged_points > 0);
  CHECK(max_rel_vs(m, "ghost.pvtu", rayint::test::analytic_linear_ray) <= test::Tolerances::exact_rel);
}

TEST_CASE("markers are not fields: a file with tags only gets one line listing its arrays", "[mesh][readers]") {
  const std::string msg = rayint::test::input_error_of([] { read_any("markers-only.vtu"); });
  CHECK(msg == kDir + "markers-only.vtu: UnstructuredGrid/Piece/PointData: no field to integrate: no one-component "
                      "point or cell array that is not a region marker (arrays: \"gmsh:physical\" (cell, 1 component, "
                      "a marker))");
  // Named, a marker may still be used (the user asked for it).
  CHECK(read_any("markers-only.vtu", {"gmsh:physical"}).cell_scalars.size() == 197);
}

TEST_CASE("cell data is integrated constant per cell, exactly, or averaged to points as ParaView does", "[mesh][readers]") {
  for (const std::string file : {"cell-data.vtu", "cell-data.vtk"}) {
    INFO(file);
    const nlohmann::json& o = oracle()[file];
    const TetMesh m = read_any(file);
    CHECK(m.info.scalar == "c");  // "region" (a marker) is listed, not taken
    CHECK(m.info.scalar_association == "cell");
    const auto& c = o["cell_arrays"]["c"]["values"];
    REQUIRE(m.cell_scalars.size() == c.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < c.size(); ++i) differ += m.cell_scalars[i] != c[i].get<double>();
    CHECK(differ == 0);
    const double rel = max_rel_vs(m, file, analytic_cells);
    WARN(file << ": cell field, max rel |I - I_two_constant_segments| over 500 rays = " << rel);
    CHECK(rel <= test::Tolerances::exact_rel);
    // On request: point data as vtkCellDataToPointData makes it (plain average over the cells
    // using the point), bit for bit.
    const TetMesh p = read_any(file, {"", true});
    const auto& want = oracle()["cell-data.vtu"]["c2p"];
    REQUIRE(p.scalars.size() == want.size());
    CHECK(p.cell_scalars.empty());
    differ = 0;
    for (std::size_t i = 0; i < want.size(); ++i) differ += p.scalars[i] != want[i].get<double>();
    CHECK(differ == 0);
  }
}

TEST_CASE("choosing the array: the active scalars by default, any point or cell array by name", "[mesh][readers]") {
  CHECK(read_any("several.vtu").info.scalar == "s");
  const TetMesh t = read_any("several.vtu", {"t"});
  const auto& tv = oracle()["several.vtu"]["point_arrays"]["t"]["values"];
  REQUIRE(t.scalars.size() == tv.size());
  for (std::size_t i = 0; i < tv.size(); ++i) CHECK(t.scalars[i] == tv[i].get<double>());
  CHECK(read_any("several.vtu", {"c"}).info.scalar_association == "cell");
  CHECK(rayint::test::input_error_of([] { read_any("several.vtu", {"v"}); }) ==
        kDir + "several.vtu: UnstructuredGrid/Piece/PointData: array \"v\" has 3 components; the scalar needs 1");
  const std::string none = rayint::test::input_error_of([] { read_any("several.vtu", {"nope"}); });
  CHECK(none == kDir + "several.vtu: UnstructuredGrid/Piece/PointData: no array named \"nope\" (arrays: \"s\" (point, 1 "
                       "component), \"t\" (point, 1 component), \"v\" (point, 3 components), \"c\" (cell, 1 component))");
  // A mesh case names it with "scalar_field".
  rayint::test::TempDir dir;
  dir.write("c.json", R"({"name": "c", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh_file": ")" + kDir + R"(several.vtu", "scalar_field": "t", "cell_data": "constant",
    "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  CHECK(read_mesh_case_file((dir.path / "c.json").string()).mesh.info.scalar == "t");
}

TEST_CASE("legacy ASCII float points are read as float32, as VTK reads them", "[mesh][readers]") {
  const TetMesh ascii = read_any("torus-ascii.vtk");
  const TetMesh binary = read_any("torus-binary.vtk");
  check_points(ascii, oracle()["torus-ascii.vtk"]["points"]);
  check_points(binary, oracle()["torus-binary.vtk"]["points"]);
  // VTK 9.1's legacy ASCII writer prints floats with 6 significant digits ("%g"), so the ASCII
  // file is another mesh than the binary one; what matters is reading each as VTK does.
  const auto& s = oracle()["torus-ascii.vtk"]["point_arrays"]["s"]["values"];
  REQUIRE(ascii.scalars.size() == s.size());
  for (std::size_t i = 0; i < s.size(); ++i) CHECK(ascii.scalars[i] == s[i].get<double>());
  REQUIRE(ascii.points.size() == binary.points.size());
  // What reading the same text as double gives (the reader before issue 27): another mesh.
  std::ifstream in(kDir + "torus-ascii.vtk");
  std::string line;
  while (std::getline(in, line) && line.rfind("POINTS", 0) != 0) {}
  TetMesh as_double = ascii;
  for (auto& p : as_double.points)
    for (int k = 0; k < 3; ++k) {
      std::string w;
      in >> w;
      p[k] = std::strtod(w.c_str(), nullptr);
    }
  TetMesh a = ascii, d = as_double;
  repair_tet_mesh(a, "a");
  repair_tet_mesh(d, "d");
  const TetTraversal ta(a, "a"), td(d, "d");
  const TransferFunctions tf = test_tf();
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  double worst = 0.0;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  for (int i = 0; i < 300; ++i) {
    const ViewRay r{Vec3(u(rng), u(rng), 3.0), Vec3(0.1 * u(rng), 0.1 * u(rng), -1.0)};
    const RayResult x = exact->integrate(mesh_ray(ta, r, {0, 0, 0}), nullptr);
    const RayResult y = exact->integrate(mesh_ray(td, r, {0, 0, 0}), nullptr);
    for (int c = 0; c < kChannels; ++c) worst = std::max(worst, std::fabs(x.intensity[c] - y.intensity[c]));
  }
  WARN("torus: read as float32 == VTK's points bit for bit; read as double the intensities differ by up to " << worst);
  CHECK(worst > 1e-9);  // the float32 reading matters: the double reading is another mesh
}

TEST_CASE("legacy STRUCTURED_POINTS and .pvti pieces read as VTK's image", "[mesh][readers][grid]") {
  for (const std::string file : {"wavelet-ascii.vtk", "wavelet-binary.vtk", "wavelet.pvti"}) {
    INFO(file);
    const nlohmann::json& o = oracle()[file];
    const VoxelGrid g = read_voxel_grid_file(kDir + file);
    const auto& e = o["extent"];
    for (int a = 0; a < 3; ++a) {
      const auto ai = static_cast<std::size_t>(a);
      CHECK(g.dims()[ai] == e[2 * ai + 1].get<int>() - e[2 * ai].get<int>() + 1);
      CHECK(g.spacing()[a] == o["spacing"][ai].get<double>());
      CHECK(g.origin()[a] == o["origin"][ai].get<double>() + e[2 * ai].get<double>() * o["spacing"][ai].get<double>());
    }
    const auto& v = o["point_arrays"]["RTData"]["values"];
    REQUIRE(g.values().size() == v.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < v.size(); ++i) differ += g.values()[i] != v[i].get<double>();
    CHECK(differ == 0);
  }
  CHECK(rayint::test::input_error_of([] { read_voxel_grid_file(kDir + "wavelet-ascii.vtk", "nope"); }) ==
        kDir + "wavelet-ascii.vtk: POINT_DATA: no point array named \"nope\" (arrays: \"RTData\" (point, 1 component))");
  CHECK(rayint::test::input_error_of([] { read_vtk_legacy(kDir + "wavelet-ascii.vtk"); }).find("STRUCTURED_POINTS is image data, not a mesh") !=
        std::string::npos);
  CHECK(rayint::test::input_error_of([] { read_voxel_grid_file(kDir + "cell-data.vtk"); }).find("UNSTRUCTURED_GRID is a mesh, not an image") !=
        std::string::npos);
}

TEST_CASE("10-node tetrahedra from gmsh, VTK and TetGen are read by one rule: corners and mid-edge nodes", "[mesh][readers][tet10]") {
  // Every reader keeps the corners as the tet and the six mid-edge nodes in VTK's order
  // (tests/test_tet10.cpp checks the values against vtkQuadraticTetra); the cell readers keep
  // them as quadratic tetra cells with the same nodes, in every reader alike (curved ones are
  // integrated there; --cells split refuses them: tests/test_quadratic_cells_mesh.cpp).
  for (const std::string file : {"box-o2-22.msh", "box-o2-41.msh", "tet10.vtu", "cube-o2.1.ele"}) {
    INFO(file);
    const TetMesh m = read_any(file);
    CHECK(m.edge_nodes.size() == m.tets.size());
    CHECK(check_tet10_edges(m).straight());
    const CellMesh cells = read_cell_mesh_file(kDir + file);
    REQUIRE(cells.cell_count() == m.tets.size());
    for (std::size_t c = 0; c < cells.cell_count(); ++c) {
      REQUIRE(cells.types[c] == MeshCellType::quadratic_tetra);
      for (std::size_t k = 0; k < 10; ++k) {
        const std::int32_t p = k < 4 ? m.tets[c][k] : m.edge_nodes[c][k - 4];
        CHECK(cells.points[static_cast<std::size_t>(cells.cell(c)[k])] == m.points[static_cast<std::size_t>(p)]);
      }
    }
  }
}

TEST_CASE("overlapping tetrahedra: VTK's Append of two shifted boxes is found, conforming meshes pass", "[mesh][readers][check]") {
  const TetMesh overlap = read_any("overlap.vtu");
  const auto pair = find_overlapping_tets(overlap);
  REQUIRE(pair.has_value());
  // The two boxes: cells 0-161 and 162-323 of the file; an overlapping pair takes one from each.
  CHECK(pair->first < 162);
  CHECK(pair->second >= 162);
  CHECK(tets_overlap(overlap, pair->first, pair->second));
  CHECK(find_overlapping_tets(overlap, OverlapScope::disjoint_pairs).has_value());
  const std::string msg = rayint::test::input_error_of([&] { refuse_overlapping_tets(overlap, "overlap.vtu", "Cells"); });
  CHECK(msg.rfind("overlap.vtu: Cells: tetrahedra 0 (cell 0 of the file) and ", 0) == 0);
  CHECK(msg.find(" overlap (their interiors intersect") != std::string::npos);
  // Conforming meshes written by gmsh, TetGen, VTK (with pieces and ghosts): nothing found, with
  // every candidate pair tested.
  for (const std::string file : {"box-22.msh", "boundary.vtu", "torus-binary.vtk", "cell-data.vtu", "ghost.pvtu"}) {
    INFO(file);
    CHECK_FALSE(find_overlapping_tets(read_any(file)).has_value());
  }
  // A mesh case refuses it (exit 2, one line), whatever --strict-mesh says.
  rayint::test::TempDir dir;
  dir.write("o.json", R"({"name": "o", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh_file": ")" + kDir + R"(overlap.vtu", "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  const auto r = rayint::test::run_cli(dir.path, "eval o.json --methods exact --no-timing -o out.json");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("rayint: error: " + kDir + "overlap.vtu: Cells: tetrahedra ", 0) == 0);
  CHECK_FALSE(fs::exists(dir.path / "out.json"));
}

TEST_CASE("CLI: mesh info lists cells by type, arrays and the scalar, --check exits 1 on an overlap", "[mesh][readers][cli]") {
  rayint::test::TempDir dir;
  const auto ok = rayint::test::run_cli(dir.path, "mesh info " + kDir + "boundary.vtu --check --format json");
  REQUIRE(ok.status == 0);
  const auto j = nlohmann::json::parse(ok.out);
  CHECK(j["tets"] == 197);
  CHECK(j["cells_by_type"]["triangle"] == nlohmann::json({{"read", 156}, {"skipped", 156}}));
  CHECK(j["cells_by_type"]["tetra"] == nlohmann::json({{"read", 197}, {"skipped", 0}}));
  CHECK(j["skipped_cells"] == 200);
  CHECK(j["scalar"]["name"] == "s");
  CHECK(j["arrays"].size() == 3);
  CHECK(j["arrays"][1]["name"] == "gmsh:physical");
  CHECK(j["arrays"][1]["marker"] == true);
  CHECK(j["orientation"]["positive"] == 197);
  CHECK(j["check"]["overlap"] == false);
  const auto bad = rayint::test::run_cli(dir.path, "mesh info " + kDir + "overlap.vtu --check");
  CHECK(bad.status == 1);
  CHECK(bad.out.find("check: cells ") != std::string::npos);
  CHECK(bad.err.find("tetrahedra overlap (cells ") != std::string::npos);
  // gmsh's legacy file of 10-node tetrahedra carries no field: one line, exit 2, nothing on stdout.
  const auto missing = rayint::test::run_cli(dir.path, "mesh info " + kDir + "box-o2-gmsh.vtk");
  CHECK(missing.status == 2);
  CHECK(missing.out.empty());
  CHECK(missing.err.find("no field to integrate") != std::string::npos);
}

// vtk_legacy_fuzzer, 2026-12-04: a cell point count or a cell type beyond long long's range was
// converted from double (undefined behaviour, caught by UBSan); both are now one-line refusals.
TEST_CASE("fuzz regression: huge cell counts and cell types in a legacy file are one-line refusals", "[mesh][readers][fuzz]") {
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                           "0 0 0 1 0 0 0 1 0 0 0 1\n";
  const std::string count = rayint::test::input_error_of([&] { parse_vtk_legacy(head + "CELLS 1 5\n2e62 0 1 2 3\nCELL_TYPES 1\n10\n", "f.vtk"); });
  CHECK(count.rfind("f.vtk: CELLS[0]: point count 2", 0) == 0);
  const std::string type = rayint::test::input_error_of([&] { parse_vtk_legacy(head + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n1.7e60\n", "f.vtk"); });
  CHECK(type.rfind("f.vtk: CELL_TYPES[0]: not a cell type: ", 0) == 0);
}
