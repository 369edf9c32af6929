// Meshes of hexahedra, wedges, pyramids and voxels as gmsh, VTK's writers and meshio write them
// (tests/fixtures/readers/cells-*, made by generate-cells.sh with the real tools), read into
// CellMeshes and checked against what VTK's and meshio's own readers read (cells-expected.json);
// `--cells split` checked tetrahedron for tetrahedron against VTK 9.1's vtkDataSetTriangleFilter
// (*-vtksplit.vtu); the tetrahedral path refuses them with one line; bad structured grids are one
// line naming the file and the field (tag [cellmesh]).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/tet_traversal.hpp"

using namespace rayint;
using rayint::test::TempDir;

namespace {

const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/";

// The field generate_cells.py writes at every point.
double written_field(const Vec3& p) {
  return 0.5 + 0.3 * std::sin(2 * p.x()) * std::cos(p.y()) + 0.25 * p.z() + 0.2 * p.x() * p.y() * p.z();
}

nlohmann::json expected() {
  std::ifstream in(kDir + "cells-expected.json");
  return nlohmann::json::parse(in);
}

std::map<std::string, long> counts_by_id(const CellMesh& m) {
  std::map<std::string, long> n;
  for (MeshCellType t : m.types) ++n[std::to_string(static_cast<int>(t))];
  return n;
}

std::multiset<std::array<std::int32_t, 4>> tet_set(const TetMesh& m) {
  std::multiset<std::array<std::int32_t, 4>> out;
  for (auto t : m.tets) {
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

}  // namespace

TEST_CASE("cell meshes from gmsh, VTK and meshio read as VTK and meshio read them", "[cellmesh]") {
  const nlohmann::json want = expected();
  for (const auto& [file, w] : want.items()) {
    INFO(file);
    const CellMesh m = read_cell_mesh_file(kDir + file);
    CHECK(m.points.size() == w["points"].get<std::size_t>());
    std::map<std::string, long> wc;
    for (const auto& [id, n] : w["volume_cells_by_vtk_type"].items()) wc[id] = n.get<long>();
    CHECK(counts_by_id(m) == wc);
    // Every point keeps its own value (a node is never separated from its scalar): the value
    // generate_cells.py computed from the point's coordinates with numpy. The legacy .vtk writers
    // (VTK's and meshio's) round what they write (VTK's legacy writer to 9 significant digits:
    // 1e-8 covers it), meshio's ASCII .vtu to 12 (%.11e: 1e-11); the others hold the doubles
    // (%.17g, binary, or VTK's XML ASCII), so what is left is numpy's sin/cos against glibc's
    // (a few ulp: 1e-15).
    const double tolerance = file.find(".vtk") != std::string::npos      ? 1e-8
                             : file.find("meshio") != std::string::npos ? 1e-11
                                                                        : 1e-15;
    REQUIRE(m.scalars.size() == m.points.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < m.points.size(); ++i) worst = std::max(worst, std::abs(m.scalars[i] - written_field(m.points[i])));
    CAPTURE(worst);
    CHECK(worst <= tolerance);
  }
}

TEST_CASE("gmsh's prisms and VTK's documented wedges have opposite corner Jacobians, both accepted", "[cellmesh]") {
  // gmsh's reference prism has a positive Jacobian (gmsh manual, "Node ordering"); VTK's wedge
  // documentation (vtkWedge.h) puts the normal of (0, 1, 2) away from (3, 4, 5): the mirror.
  for (const std::string f : {"cells-prism-22.msh", "cells-prism-41.msh"}) {
    INFO(f);
    const CellMesh m = read_cell_mesh_file(kDir + f);
    long positive = 0;
    for (std::size_t c = 0; c < m.cell_count(); ++c) positive += cell_orientation(m, c) > 0 ? 1 : 0;
    CHECK(positive == static_cast<long>(m.cell_count()));
  }
  // meshio turns gmsh's prisms into VTK's order when it writes a .vtk (it permutes the nodes and
  // their values together): VTK's orientation.
  const CellMesh meshio = read_cell_mesh_file(kDir + "cells-prism-meshio.vtk");
  for (std::size_t c = 0; c < meshio.cell_count(); ++c) CHECK(cell_orientation(meshio, c) == -1);
  const CellMesh vtk_all = read_cell_mesh_file(kDir + "cells-all-types.vtu");
  for (std::size_t c = 0; c < vtk_all.cell_count(); ++c) {
    INFO(mesh_cell_name(vtk_all.types[c]));
    CHECK(cell_orientation(vtk_all, c) == (vtk_all.types[c] == MeshCellType::wedge ? -1 : 1));
  }
  // gmsh's hexahedra (both blocks, the twisted one too) and pyramids are positive in VTK's sense.
  for (const std::string f : {"cells-hex-41.msh", "cells-mixed-22.msh"}) {
    const CellMesh m = read_cell_mesh_file(kDir + f);
    for (std::size_t c = 0; c < m.cell_count(); ++c) CHECK(cell_orientation(m, c) == 1);
  }
}

TEST_CASE("gmsh's interface and boundary quadrangles are skipped and counted, never cells", "[cellmesh]") {
  // cells-hex.geo: 11 surfaces (10 outer, 1 between the blocks) of 3 x 3 quadrangles, written with
  // Mesh.SaveAll; 2 blocks of 27 hexahedra.
  const CellMesh m = read_cell_mesh_file(kDir + "cells-hex-22.msh");
  CHECK(m.info.skipped_by_type.at("quad") == 99);
  CHECK(m.cell_count() == 54);
  const TetMesh split = split_cells(m);
  CHECK(split.tets.size() >= 5 * 54);
}

TEST_CASE("split_cells gives the tetrahedra of VTK 9.1's vtkDataSetTriangleFilter one for one", "[cellmesh]") {
  const nlohmann::json want = expected();
  for (const std::string f : {"cells-all-types.vtu", "cells-twisted.vts", "cells-odd.vtr", "cells-mixed-41.msh"}) {
    INFO(f);
    CellSplitCounts counts;
    const TetMesh mine = split_cells(read_cell_mesh_file(kDir + f), &counts);
    const TetMesh vtk = read_vtu(kDir + f.substr(0, f.rfind('.')) + "-vtksplit.vtu");
    CHECK(mine.tets.size() == want[f]["vtk_split_tets"].get<std::size_t>());
    CHECK(tet_set(mine) == tet_set(vtk));
    CHECK(counts.structured == (f.find(".vts") != std::string::npos || f.find(".vtr") != std::string::npos));
  }
}

TEST_CASE("the tetrahedral path refuses hexahedra, wedges, pyramids and voxels with one line naming --cells split", "[cellmesh]") {
  for (const std::string f : {"cells-hex-41.msh", "cells-prism-22.msh", "cells-all-types.vtu", "cells-all-types.vtk",
                              "cells-twisted.vts", "cells-odd.vtr"}) {
    INFO(f);
    try {
      (void)read_mesh_file(kDir + f);
      FAIL("accepted");
    } catch (const InputError& e) {
      const std::string what = e.what();
      CHECK(what.rfind(kDir + f + ": ", 0) == 0);
      CHECK(what.find("--cells split") != std::string::npos);
      CHECK(what.find('\n') == std::string::npos);
    }
  }
}

TEST_CASE("bad structured grids are one line naming the file and the field", "[cellmesh]") {
  const std::string vtr = R"(<VTKFile type="RectilinearGrid" version="1.0" byte_order="LittleEndian">
<RectilinearGrid WholeExtent="0 1 0 1 0 1"><Piece Extent="0 1 0 1 0 1"><PointData Scalars="s">
<DataArray type="Float64" Name="s" format="ascii">0 1 2 3 4 5 6 7</DataArray></PointData>
<Coordinates><DataArray type="Float64" Name="a" format="ascii">0 1</DataArray>
<DataArray type="Float64" Name="b" format="ascii">0 1</DataArray>COORDZ</Coordinates></Piece></RectilinearGrid></VTKFile>)";
  auto with = [&](const std::string& z) {
    std::string s = vtr;
    s.replace(s.find("COORDZ"), 6, z);
    return s;
  };
  CHECK(parse_vtr(with(R"(<DataArray type="Float64" Name="odd name" format="ascii">0 2</DataArray>)"), "g.vtr").cell_count() == 1);
  CHECK_THROWS_WITH(parse_vtr(with(""), "g.vtr"),
                    "g.vtr: RectilinearGrid/Piece/Coordinates: needs three DataArrays (x, y, z), got 2");
  CHECK_THROWS_WITH(parse_vtr(with(R"(<DataArray type="Float64" Name="c" format="ascii">1 0</DataArray>)"), "g.vtr"),
                    Catch::Contains("g.vtr: RectilinearGrid/Piece/Coordinates/DataArray[2]: coordinates must increase"));
  std::string flat = with(R"(<DataArray type="Float64" Name="c" format="ascii">0 1</DataArray>)");
  flat.replace(flat.find("0 1 0 1 0 1"), 11, "0 1 0 1 0 0");
  flat.replace(flat.find("0 1 0 1 0 1"), 11, "0 1 0 1 0 0");
  CHECK_THROWS_WITH(parse_vtr(flat, "g.vtr"), Catch::StartsWith("g.vtr: RectilinearGrid/Piece: Extent is flat on axis z"));
  CHECK_THROWS_WITH(parse_vts(vtr, "g.vts"), Catch::StartsWith("g.vts: "));
}

TEST_CASE("rayint mesh info reports hexahedra, wedges, pyramids and voxels by type", "[cellmesh][cli]") {
  TempDir dir;
  const auto r = rayint::test::run_cli(dir.path, "mesh info '" + kDir + "cells-mixed-41.msh' --format json");
  REQUIRE(r.status == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j["cells_by_type"]["hexahedron"]["read"] == 8);
  CHECK(j["cells_by_type"]["pyramid"]["read"] == 4);
  CHECK(j["cells_by_type"]["tetra"]["read"] == 105);
  CHECK(j["cells"] == 117);
  CHECK(j["cell_orientation"]["pyramid"]["positive"] == 4);
  CHECK(j["integrated"].get<std::string>().find("--cells split") != std::string::npos);
  const auto t = rayint::test::run_cli(dir.path, "mesh info '" + kDir + "cells-odd.vtr'");
  CHECK(t.status == 0);
  CHECK(t.out.find("voxel 12") != std::string::npos);
  CHECK(t.out.find("structured 4 x 3 x 3 points") != std::string::npos);
}

TEST_CASE("split meshes are conforming and rays through shared faces, edges and vertices keep their length", "[cellmesh]") {
  // Conforming: every triangle of the split is a face of one tetrahedron (boundary) or two
  // (interior), never three; a non-conforming split (neighbours choosing different diagonals of a
  // shared quadrangle) would leave faces used once inside the volume.
  for (const std::string f : {"cells-hex-41.msh", "cells-mixed-22.msh", "cells-prism-41.msh", "cells-twisted.vts",
                              "cells-odd.vtr", "cells-all-types.vtk"}) {
    INFO(f);
    const CellMesh cells = read_cell_mesh_file(kDir + f);
    const TetMesh m = split_cells(cells);
    std::map<std::array<std::int32_t, 3>, int> uses;
    for (const auto& t : m.tets)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<std::int32_t, 3> face{};
        for (int i = 0, j = 0; i < 4; ++i)
          if (i != skip) face[static_cast<std::size_t>(j++)] = t[static_cast<std::size_t>(i)];
        std::sort(face.begin(), face.end());
        ++uses[face];
      }
    long once = 0, more = 0;
    for (const auto& [face, n] : uses) {
      if (n == 1) ++once;
      if (n > 2) ++more;
    }
    CHECK(more == 0);
    // The boundary triangles of the split are the split boundary faces of the cells: a quad face
    // used by one cell gives 2, a triangle face 1. Counted from the cells' own faces by node sets.
    std::map<std::vector<std::int32_t>, int> cell_faces;
    static const std::map<MeshCellType, std::vector<std::vector<int>>> faces = {
        {MeshCellType::tetra, {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}}},
        {MeshCellType::hexahedron, {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}},
        {MeshCellType::voxel, {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {1, 3, 7, 5}, {3, 2, 6, 7}, {2, 0, 4, 6}}},
        {MeshCellType::wedge, {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}}},
        {MeshCellType::pyramid, {{0, 1, 2, 3}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}}};
    for (std::size_t c = 0; c < cells.cell_count(); ++c)
      for (const auto& fl : faces.at(cells.types[c])) {
        std::vector<std::int32_t> key;
        for (int k : fl) key.push_back(cells.cell(c)[k]);
        std::sort(key.begin(), key.end());
        ++cell_faces[key];
      }
    long boundary_triangles = 0;
    for (const auto& [key, n] : cell_faces) {
      CHECK(n <= 2);
      if (n == 1) boundary_triangles += key.size() == 4 ? 2 : 1;
    }
    CHECK(once == boundary_triangles);
  }
}

TEST_CASE("rays along grid lines and through cell corners of a split .vtr cross the whole box", "[cellmesh]") {
  // cells-odd.vtr: x in {0, 0.2, 0.7, 1}, y in {-0.5, 0.1, 0.4}, z in {0, 0.3, 1.1}. Rays along x
  // through a cell interior, along a grid line (edges shared by four voxels), and diagonally
  // through grid vertices: the crossings must tile the chord exactly once.
  TetTraversal mesh(split_cells(read_cell_mesh_file(kDir + "cells-odd.vtr")), "cells-odd.vtr");
  struct Case {
    Vec3 origin, direction;
    double length;
  };
  const Vec3 diag = Vec3(1.0, 0.9, 1.1).normalized();
  const std::vector<Case> cases = {
      {{-1, 0.05, 0.5}, {1, 0, 0}, 1.0},            // interior of a row of cells
      {{-1, 0.1, 0.3}, {1, 0, 0}, 1.0},             // along a grid line: edges of 4 voxels
      {{0.2, 0.1, -1}, {0, 0, 1}, 1.1},             // along a grid line in z
      {{0.2, -2, 0.3}, {0, 1, 0}, 0.9},             // along a grid line in y, through vertices
      {Vec3(0, -0.5, 0) - diag, diag, std::sqrt(1.0 + 0.81 + 1.21)},  // corner to corner
  };
  for (const Case& c : cases) {
    INFO(c.origin.transpose() << " -> " << c.direction.transpose());
    RayTrace trace;
    TraversalStats stats;
    mesh.trace(ViewRay{c.origin, c.direction}, trace, &stats);
    double total = 0.0, last = -INFINITY;
    for (const CellCrossing& x : trace.crossings) {
      CHECK(x.t_in >= last);
      total += x.t_out - x.t_in;
      last = x.t_out;
    }
    CHECK(stats.budget_exhausted == 0);
    CHECK(std::abs(total - c.length) <= 1e-12 * c.length);
  }
}

TEST_CASE("CLI: --cells split integrates a .vtr and says split, without it the own mode, methods refused in one line", "[cellmesh][cli]") {
  TempDir dir;
  dir.write("odd.json", R"({"name": "odd", "transfer_function": {"density": [[0, 1], [1.5, 2]], "color": [[0, 1]]},
    "mesh_file": ")" + kDir + R"(cells-odd.vtr",
    "rays": [{"origin": [-1, 0.05, 0.5], "direction": [1, 0, 0]}, {"origin": [-1, 0.1, 0.3], "direction": [1, 0, 0]}],
    "camera": {"position": [0.5, 0, 4], "look_at": [0.5, 0, 0.5], "fov_deg": 30, "width": 6, "height": 5}})");
  const auto before = dir.entries();
  // Without --cells split the voxels are integrated in their own interpolation ("mode": "own",
  // mesh/cell_traversal.hpp); the segment methods do not apply there: one line, exit 2.
  const auto refused = test::run_cli(dir.path, "eval odd.json --methods exact --no-timing -o out.json");
  CHECK(refused.status == 2);
  CHECK(refused.out.empty());
  CHECK(refused.err.find("--methods") != std::string::npos);
  CHECK(refused.err.find("--cells split") != std::string::npos);
  CHECK(test::line_count(refused.err) == 1);
  CHECK(dir.entries() == before);
  const auto own = test::run_cli(dir.path, "eval odd.json -q");
  REQUIRE(own.status == 0);
  const auto jo = nlohmann::json::parse(own.out);
  CHECK(jo["mode"] == "own");
  CHECK(jo["cases"][0]["cells"]["voxel"] == 12);
  CHECK(jo["cases"][0]["rays"].size() == 2);
  CHECK(jo["cases"][0]["failed"] == 0);
  CHECK(jo["cases"][0]["max_abs_error"].get<double>() <= 1e-13);  // against the 50-digit cell reference
  const auto e = test::run_cli(dir.path, "eval odd.json --cells split --methods exact --no-timing");
  REQUIRE(e.status == 0);
  const auto j = nlohmann::json::parse(e.out);
  const auto& cells = j["cases"][0]["mesh_repairs"]["cells"];
  CHECK(cells["mode"] == "split");
  CHECK(cells["cells_split_by_type"]["voxel"] == 12);
  CHECK(cells["approximation"].get<std::string>().find("vtkDataSetTriangleFilter") != std::string::npos);
  const auto r = test::run_cli(dir.path, "render odd.json --cells split -o img.png --stats s.json");
  REQUIRE(r.status == 0);
  CHECK(r.err.find("--cells split: 12 cells tetrahedralised into 60 tetrahedra") != std::string::npos);
  const auto s = nlohmann::json::parse(test::slurp(dir.path / "s.json"));
  CHECK(s["mesh"]["repairs"]["cells"]["mode"] == "split");
  CHECK(s["mesh"]["tets"] == 60);
  const auto bad = test::run_cli(dir.path, "eval odd.json --cells whole -o out2.json");
  CHECK(bad.status == 2);
}

TEST_CASE("mesh_cell_nodes gives VTK's node count for the cell types a CellMesh holds and 0 for any other", "[cellmesh]") {
  // The counts of VTK's file-format documentation (VTK_TETRA 4, VTK_VOXEL 8, VTK_HEXAHEDRON 8,
  // VTK_WEDGE 6, VTK_PYRAMID 5, VTK_QUADRATIC_TETRA 10, VTK_QUADRATIC_HEXAHEDRON 20,
  // VTK_QUADRATIC_WEDGE 15, VTK_QUADRATIC_PYRAMID 13, VTK_TRIQUADRATIC_HEXAHEDRON 27,
  // VTK_BIQUADRATIC_QUADRATIC_WEDGE 18).
  const std::map<int, int> documented{{10, 4}, {11, 8}, {12, 8}, {13, 6}, {14, 5}, {24, 10}, {25, 20}, {26, 15},
                                      {27, 13}, {29, 27}, {32, 18}};
  for (const auto& [id, nodes] : documented) {
    INFO("VTK id " << id);
    CHECK(mesh_cell_nodes(id) == nodes);
  }
  // Not a type of MeshCellType: points, lines and faces (1, 3, 5, 9), prisms rayint does not read
  // (15, 16), the triquadratic pyramid (37), the polyhedron (42), unknown ids.
  for (const long long id : {0LL, 1LL, 3LL, 5LL, 9LL, 15LL, 16LL, 37LL, 42LL, 200LL, -1LL}) {
    INFO("VTK id " << id);
    CHECK(mesh_cell_nodes(id) == 0);
  }
}
