// Meshes that TetGen, gmsh and meshio wrote (tests/fixtures/meshes/, made by its generate.sh):
// each is read, traversed and integrated, and compared with the analytic single segment through
// the cube [-1,1]^3 carrying the linear field s = 0.5 + 0.3x - 0.2y + 0.4z; and every new
// reader's bad input is one line naming the file and the field, exit 2, no output
// (tag [mesh][formats]).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <utility>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "cli_refusal.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/gmsh_reader.hpp"
#include "rayint/input/tetgen_reader.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "tolerances.hpp"
#include "mesh_case_fixtures.hpp"
#include "input_text.hpp"

using namespace rayint;
using rayint::test::TempDir;

namespace {

const std::string kDir = RAYINT_SOURCE_DIR + "/tests/fixtures/meshes/";

using rayint::test::linear_field;

std::string slurp_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Agreement {
  double max_rel = 0.0;
  int hits = 0;
  long segments = 0;
  long budget_exhausted = 0;
};

// 1000 rays from a sphere of radius 4 toward [-0.9, 0.9]^3 (every ray crosses the cube).
Agreement agree_with_analytic(const TetMesh& mesh_as_read, const std::string& name) {
  TetMesh mesh = mesh_as_read;
  repair_tet_mesh(mesh, name);
  const TetTraversal m(mesh, name);
  const TransferFunctions tf = rayint::test::mesh_field_tf();  // the integrator keeps a reference to it
  const auto exact = make_integrator(parse_method_spec("exact"), tf);
  std::mt19937_64 rng(14);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  Agreement a;
  TraversalStats stats;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o = 4.0 * Vec3(g(rng), g(rng), g(rng)).normalized();
    const ViewRay r{o, Vec3(u(rng), u(rng), u(rng)) - o};
    const Rgb bg{0.1, 0.2, 0.3};
    const Ray traced = mesh_ray(m, r, bg, &stats);
    a.segments += static_cast<long>(traced.segments.size());
    const RayResult got = exact->integrate(traced, nullptr);
    const RayResult want = exact->integrate(rayint::test::analytic_linear_ray(r, bg), nullptr);
    ++a.hits;
    for (int c = 0; c < kChannels; ++c)
      a.max_rel = std::max(a.max_rel, std::fabs(got.intensity[c] - want.intensity[c]) / std::fabs(want.intensity[c]));
  }
  a.budget_exhausted = stats.budget_exhausted;
  return a;
}

void check_fixture(const TetMesh& mesh, const std::string& name, std::size_t tets) {
  INFO(name);
  CHECK(mesh.tets.size() == tets);
  const Agreement a = agree_with_analytic(mesh, name);
  WARN(name << ": " << mesh.tets.size() << " tets, " << a.segments << " segments over " << a.hits
            << " rays, max rel |I_mesh - I_analytic| = " << a.max_rel);
  CHECK(a.segments > 2 * a.hits);
  CHECK(a.max_rel <= test::Tolerances::exact_rel);
  CHECK(a.budget_exhausted == 0);
}

// Appends a constant one-component $NodeData over node tags 1..N (N from the 4.1 $Nodes header).
std::string with_node_data(const std::string& msh41) {
  const auto at = msh41.find("$Nodes\n");
  REQUIRE(at != std::string::npos);
  std::istringstream header(msh41.substr(at + 7, 200));
  long blocks = 0, n = 0, lo = 0, hi = 0;
  header >> blocks >> n >> lo >> hi;
  REQUIRE((hi - lo + 1) == n);
  std::string out = msh41 + "$NodeData\n1\n\"s\"\n1\n0.0\n3\n0\n1\n" + std::to_string(n) + "\n";
  for (long t = lo; t <= hi; ++t) out += std::to_string(t) + " 0\n";
  return out + "$EndNodeData\n";
}

}  // namespace

TEST_CASE("TetGen output (.node + .ele) reads and integrates like the analytic cube", "[mesh][formats]") {
  // cube.1: Delaunay of 27 points, TetGen carried the field through as attribute 0.
  const TetMesh delaunay = read_tetgen(kDir + "cube.1.ele");
  for (std::size_t i = 0; i < delaunay.points.size(); ++i)
    CHECK(delaunay.scalars[i] == Approx(linear_field(delaunay.points[i])).margin(1e-15));
  check_fixture(delaunay, "tetgen cube.1", 53);
  // cubeq.1: quality mesh (625 tets, Steiner points whose attribute TetGen did not interpolate):
  // its geometry is checked with the field set here.
  TetMesh quality = read_tetgen(kDir + "cubeq.1.ele");
  assign_field(quality, linear_field);
  check_fixture(quality, "tetgen cubeq.1", 625);
  // TetGen wrote every tet positively oriented (VTK's sense): nothing to reorient.
  TetMesh copy = read_tetgen(kDir + "cubeq.1.ele");
  CHECK(repair_tet_mesh(copy, "q").reoriented == 0);
}

TEST_CASE("gmsh output (MSH 2.2 with $ElementNodeData, MSH 4.1) reads and integrates like the analytic cube", "[mesh][formats]") {
  const TetMesh m22 = read_gmsh(kDir + "box-2.2.msh");
  for (std::size_t i = 0; i < m22.points.size(); ++i)
    CHECK(m22.scalars[i] == Approx(linear_field(m22.points[i])).margin(1e-14));
  check_fixture(m22, "gmsh box-2.2.msh", 100);
  TetMesh copy = m22;
  CHECK(repair_tet_mesh(copy, "g").reoriented == 0);  // gmsh wrote every tet positive
  // gmsh saved the 4.1 file without data: it has none to offer...
  CHECK_THROWS_WITH(read_gmsh(kDir + "box-4.1.msh"),
                    Catch::StartsWith(kDir + "box-4.1.msh: $NodeData: no one-component $NodeData, $ElementNodeData or $ElementData"));
  // ...so a $NodeData is appended to gmsh's own $Entities/$Nodes/$Elements, and the field set here.
  TetMesh m41 = parse_gmsh(with_node_data(slurp_file(kDir + "box-4.1.msh")), "box-4.1.msh");
  assign_field(m41, linear_field);
  check_fixture(m41, "gmsh box-4.1.msh", 100);
}

TEST_CASE("meshio output (VTK legacy 5.1 binary/ASCII, gmsh 2.2/4.1 ASCII/binary) reads the same mesh", "[mesh][formats]") {
  const TetMesh vtk = read_vtk_legacy(kDir + "meshio-box.vtk");
  check_fixture(vtk, "meshio-box.vtk", 100);
  for (const std::string f : {"meshio-box-ascii.vtk", "meshio-box-22.msh", "meshio-box-41.msh",
                              "meshio-box-22-binary.msh", "meshio-box-41-binary.msh"}) {
    INFO(f);
    const TetMesh m = f.find(".vtk") != std::string::npos ? read_vtk_legacy(kDir + f) : read_gmsh(kDir + f);
    // The same points, tets and scalars as the binary .vtk (meshio writes every double exactly).
    CHECK(m.points == vtk.points);
    CHECK(m.tets == vtk.tets);
    CHECK(m.scalars == vtk.scalars);
  }
}

TEST_CASE("meshio-written mixed orientation: as written and reoriented agree to 1e-14", "[mesh][formats]") {
  const TetMesh as_written = read_vtk_legacy(kDir + "meshio-box-mixed.vtk");
  TetMesh repaired = as_written;
  const TetRepairs r = repair_tet_mesh(repaired, "mixed");
  CHECK(r.reoriented == 50);
  check_fixture(as_written, "meshio-box-mixed.vtk", 100);
  // Through the case reader, with the counts: the same rays on both files.
  const std::string rays = R"("rays": [{"origin": [0.3, -0.2, 5], "direction": [-0.1, 0.05, -1]},
                                       {"origin": [4, 0.1, 0.2], "direction": [-1, 0, 0.02]},
                                       {"origin": [-3, -3, -3], "direction": [1, 1.1, 0.9]}])";
  const auto case_text = [&](const std::string& file) {
    return R"({"name": "m", "transfer_function": {"density": [[-0.5, 0.2], [0.4, 1.6], [1.5, 0.4]],
      "color": [[-0.5, 0.1], [1.5, 0.9]]}, "mesh_file": ")" + file + "\", " + rays + "}";
  };
  std::optional<TetRepairs> mixed_repairs, plain_repairs;
  const Case mixed = parse_case_text(case_text("meshio-box-mixed.vtk"), kDir + "c.json", {}, &mixed_repairs);
  const Case plain = parse_case_text(case_text("meshio-box.vtk"), kDir + "c.json", {}, &plain_repairs);
  REQUIRE(mixed_repairs);
  REQUIRE(plain_repairs);
  CHECK(mixed_repairs->reoriented == 50);
  CHECK(plain_repairs->reoriented == 0);
  const auto exact = make_integrator(parse_method_spec("exact"), mixed.transfer);
  double worst = 0.0;
  for (std::size_t i = 0; i < mixed.rays.size(); ++i) {
    const RayResult a = exact->integrate(mixed.rays[i], nullptr), b = exact->integrate(plain.rays[i], nullptr);
    for (int c = 0; c < kChannels; ++c) worst = std::max(worst, std::fabs(a.intensity[c] - b.intensity[c]));
  }
  CHECK(worst <= test::Tolerances::reorient_abs);
  CHECK_THROWS_WITH(parse_case_text(case_text("meshio-box-mixed.vtk"), kDir + "c.json", MeshReadOptions{true}),
                    Catch::Contains("meshio-box-mixed.vtk: CELLS[0]: inverted tetrahedron"));
}

TEST_CASE("Mesh cases read .ele and .msh through the mesh_file dispatch", "[mesh][formats]") {
  for (const std::string f : {"cube.1.ele", "box-2.2.msh", "meshio-box-41-binary.msh"}) {
    INFO(f);
    const Case c = parse_case_text(R"({"name": "m", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
      "mesh_file": ")" + f + R"(", "rays": [{"origin": [0.1, 0.2, 5], "direction": [0, 0, -1]}]})",
                                   kDir + "c.json");
    REQUIRE(c.rays[0].segments.size() >= 2);
    double len = 0.0;
    for (const Segment& s : c.rays[0].segments) len += s.length;
    CHECK(len == Approx(2.0).epsilon(1e-14));
    CHECK(c.rays[0].segments.front().scalar_far == Approx(linear_field(Vec3(0.1, 0.2, -1))).epsilon(1e-13));
  }
}

namespace {

std::string tetgen_error(const std::string& node, const std::string& ele) {
  return test::input_error_of([&] { parse_tetgen(node, "t.node", ele, "t.ele"); });
}

std::string gmsh_error(const std::string& msh) {
  return test::input_error_of([&] { parse_gmsh(msh, "g.msh"); });
}

// `s` with the first `from` replaced by `to` (which must be there): input_text.hpp's, by the
// short name the tables below use.
std::string replace(std::string s, const std::string& from, const std::string& to) {
  return rayint::test::replace_first(std::move(s), from, to);
}

const std::string kNode = "# a tet\n4 3 1 0\n1 0 0 0 0.5\n2 1 0 0 1\n3 0 1 0 2\n4 0 0 1 3\n";
const std::string kEle = "1 4 0\n1 1 2 3 4\n";
const std::string kMsh22 =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
    "$Elements\n2\n1 2 2 0 1 1 2 3\n2 4 2 0 1 1 2 3 4\n$EndElements\n"
    "$NodeData\n1\n\"s\"\n1\n0.0\n3\n0\n1\n4\n1 0.5\n2 1\n3 2\n4 3\n$EndNodeData\n";

}  // namespace

TEST_CASE("TetGen reader: every problem is one line naming the file and the field", "[mesh][formats]") {
  REQUIRE(tetgen_error(kNode, kEle) == "(no error)");
  struct Bad {
    std::string node, ele, expect;
  };
  const Bad bad[] = {
      {replace(kNode, "4 3 1 0", "4 2 1 0"), kEle, "t.node: header, line 2: dimension must be 3"},
      {replace(kNode, "4 3 1 0", "4 3 0 0"), kEle, "t.node: header, line 2: no point attributes"},
      {replace(kNode, "3 0 1 0 2", "7 0 1 0 2"), kEle, "t.node: node[2], line 5: index 7 out of sequence (expected 3)"},
      {replace(kNode, "2 1 0 0 1", "2 1 0 nan 1"), kEle, "t.node: node[1], line 4: expected a finite number, got \"nan\""},
      {replace(kNode, "4 0 0 1 3\n", ""), kEle, "t.node: node[3], line 5: unexpected end of file"},
      {kNode, replace(kEle, "1 1 2 3 4", "1 1 2 3 5"), "t.ele: ele[0], line 2: 5 is out of range [1, 4]"},
      {kNode, replace(kEle, "1 4 0", "1 6 0"), "t.ele: header, line 1: nodes per tetrahedron must be 4 or 10"},
      {kNode, replace(kEle, "1 1 2 3 4", "1 1 2 3"), "t.ele: ele[0], line 2: expected index n1 n2 n3 n4 [...] (5 numbers), got 4"},
      {kNode, "", "t.ele: header: unexpected end of file"},
  };
  test::check_refusal_table(bad, [](const Bad& b) { return tetgen_error(b.node, b.ele); });
}

TEST_CASE("gmsh reader: every problem is one line naming the file and the section", "[mesh][formats]") {
  REQUIRE(gmsh_error(kMsh22) == "(no error)");
  const test::BadText bad[] = {
      {replace(kMsh22, "2.2 0 8", "3.0 0 8"), "g.msh: $MeshFormat, line 2: version \"3.0\" is not read"},
      {replace(kMsh22, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", ""), "g.msh: $Nodes, line 1: the file must start with $MeshFormat"},
      {replace(kMsh22, "2 4 2 0 1 1 2 3 4", "2 5 2 0 1 1 2 3 4"), "g.msh: $Elements, line 14: element 2: 9 numbers, a 8-node hexahedron with 2 tags needs 13"},
      {replace(kMsh22, "2 4 2 0 1 1 2 3 4", "2 17 2 0 1 1 2 3 4 1 2 3 4 1 2 3 4 1 2 3 4 1 2 3 4"),
       "g.msh: $Elements, line 14: cell type quadratic hexahedron (VTK id 25): the tetrahedral paths and --cells split take "
       "linear cells only; `rayint render` integrates it in its own (isoparametric) interpolation without --cells split "
       "(gmsh element type 17)"},
      {replace(kMsh22, "2 4 2 0 1 1 2 3 4", "2 4 2 0 1 1 2 3 9"), "g.msh: $Elements (element 2): node tag 9 is not in $Nodes"},
      {replace(kMsh22, "2 1 0 0", "2 1 0 x"), "g.msh: $Nodes, line 7: expected a finite number, got \"x\""},
      {replace(kMsh22, "$EndNodes", "$EndNode"), "g.msh: $Nodes, line 10: expected $EndNodes, got \"$EndNode\""},
      {replace(kMsh22, "3 2\n4 3\n", "3 2\n"), "g.msh: $NodeData, line 28: expected tag value... (2 numbers), got 1"},
      {replace(kMsh22, "\"s\"\n1\n0.0\n3\n0\n1\n", "\"s\"\n1\n0.0\n3\n0\n3\n"), "g.msh: $NodeData, line 25: entity 1: 1 values, expected 3"},
      {kMsh22.substr(0, kMsh22.find("$NodeData")), "g.msh: $NodeData: no one-component $NodeData, $ElementNodeData or $ElementData that is not a marker"},
      {kMsh22.substr(0, kMsh22.find("$Elements")), "g.msh: $Elements: missing"},
  };
  test::check_refusal_table(bad, [](const test::BadText& b) { return gmsh_error(b.text); });
  SECTION("binary files cut short") {
    const std::string bin = slurp_file(kDir + "meshio-box-41-binary.msh");
    for (const std::size_t cut : {bin.size() / 5, bin.size() / 2, bin.size() - 40}) {
      const std::string msg = gmsh_error(bin.substr(0, cut));
      INFO(cut << ": " << msg);
      CHECK(msg.rfind("g.msh: $", 0) == 0);
      CHECK(msg.find('\n') == std::string::npos);
    }
  }
  SECTION("element node data that disagrees at a node") {
    // Two tets sharing nodes 2, 3, 4; the values are given per element, as gmsh's Save View does.
    const std::string m =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n"
        "$Elements\n2\n1 4 2 0 1 1 2 3 4\n2 4 2 0 1 2 3 5 4\n$EndElements\n"
        "$ElementNodeData\n1\n\"s\"\n1\n0.0\n3\n0\n1\n2\n1 4 0.5 1 2 3\n2 4 1 2 9 3\n$EndElementNodeData\n";
    CHECK(gmsh_error(m) == "(no error)");
    CHECK(gmsh_error(replace(m, "2 4 1 2 9 3", "2 4 1.5 2 9 3")) ==
          "g.msh: $ElementNodeData: node 2 has two values (1 and 1.5): the field is not continuous");
  }
}

TEST_CASE("CLI: bad TetGen and gmsh files exit 2 with one line and no output", "[mesh][formats]") {
  TempDir dir;
  const std::string tf = R"("transfer_function": {"density": [[0, 1]], "color": [[0, 1]]})";
  dir.write("t.node", replace(kNode, "2 1 0 0 1", "2 1 0 0"));
  dir.write("t.ele", kEle);
  dir.write("t.json", R"({"name": "t", )" + tf + R"(, "mesh_file": "t.ele",
    "rays": [{"origin": [0.1, 0.1, 5], "direction": [0, 0, -1]}]})");
  dir.write("g.msh", replace(kMsh22, "2 4 2 0 1 1 2 3 4", "2 5 2 0 1 1 2 3 4 1 2 3 4"));
  dir.write("g.json", R"({"name": "g", )" + tf + R"(, "mesh_file": "g.msh",
    "rays": [{"origin": [0.1, 0.1, 5], "direction": [0, 0, -1]}]})");
  test::check_refusals(
      dir,
      {{"eval t.json -o out.json",
        "t.node: node[1], line 4: expected index x y z [attributes] [marker] (5 numbers), got 4"},
       // g.msh's one hexahedron repeats its bottom face as its top: zero volume, nothing to
       // integrate in the own mode (mesh/cell_mesh.hpp drop_zero_volume_cells); --methods on a
       // real hexahedral mesh is refused in [cellmesh][cli].
       {"eval g.json --methods exact -o out.json", "g.msh: cells: every cell has zero volume"}},
      false);
}

TEST_CASE("CLI: eval and render --stats report the reoriented and dropped tets", "[mesh][formats]") {
  TempDir dir;
  dir.write("mixed.json", R"({"name": "m", "transfer_function": {"density": [[0, 1], [1, 2]], "color": [[0, 1]]},
    "mesh_file": ")" + kDir + R"(meshio-box-mixed.vtk",
    "rays": [{"origin": [0.1, 0.2, 5], "direction": [0, 0, -1]}],
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 30, "width": 6, "height": 5}})");
  const auto e = test::run_cli(dir.path, "eval mixed.json --methods exact --no-timing");
  REQUIRE(e.status == 0);
  const auto j = nlohmann::json::parse(e.out);
  CHECK(j["cases"][0]["mesh_repairs"] ==
        nlohmann::json({{"tets_read", 100}, {"reoriented", 50}, {"dropped_zero_volume", 0}, {"dropped_slivers", 0},
                        {"skipped_cells", 0}, {"skipped_by_type", nlohmann::json::object()}, {"ghost_cells_dropped", 0}}));
  const auto r = test::run_cli(dir.path, "render mixed.json -o img.png --stats s.json --quiet");
  REQUIRE(r.status == 0);
  const auto s = nlohmann::json::parse(test::slurp(dir.path / "s.json"));
  CHECK(s["mesh"]["repairs"]["reoriented"] == 50);
  CHECK(s["mesh"]["tets"] == 100);
  const auto strict = test::run_cli(dir.path, "eval --strict-mesh mixed.json --no-timing -o out.json");
  CHECK(strict.status == 2);
  CHECK(strict.err.find("meshio-box-mixed.vtk: CELLS[0]: inverted tetrahedron") != std::string::npos);
  CHECK(!std::filesystem::exists(dir.path / "out.json"));
}
