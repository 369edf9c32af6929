// Mesh input: VTK legacy reader/writer round trips, the reader's supported layouts, and every
// validation error (tag [mesh]).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>

#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/report/vtk_legacy_writer.hpp"
#include "rayint/mesh/mesh_generators.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "input_text.hpp"

using namespace rayint;

namespace {

// One tet, four points, positive orientation.
const char* kOneTetAscii =
    "# vtk DataFile Version 3.0\n"
    "one tet\n"
    "ASCII\n"
    "DATASET UNSTRUCTURED_GRID\n"
    "POINTS 4 float\n"
    "0 0 0  1 0 0  0 1 0  0 0 1\n"
    "CELLS 1 5\n"
    "4 0 1 2 3\n"
    "CELL_TYPES 1\n"
    "10\n"
    "POINT_DATA 4\n"
    "SCALARS s double 1\n"
    "LOOKUP_TABLE default\n"
    "0.5 1.5 2.5 3.5\n";

// `s` with the first `from` replaced by `to` (which must be there): input_text.hpp's, by the
// short name the tables below use.
std::string replace(std::string s, const std::string& from, const std::string& to) {
  return rayint::test::replace_first(std::move(s), from, to);
}

std::string error_of(const std::string& vtk) {
  return test::input_error_of([&] { parse_vtk_legacy(vtk, "m.vtk"); });
}

}  // namespace

TEST_CASE("VTK legacy round trip, ASCII and binary, is exact", "[mesh]") {
  const GeneratedMesh g = generate_mesh("linear-box", 2, 7);
  for (VtkEncoding enc : {VtkEncoding::ascii, VtkEncoding::binary}) {
    VtkWriteOptions w;
    w.encoding = enc;
    const TetMesh back = parse_vtk_legacy(encode_vtk_legacy(g.mesh, w), "rt.vtk");
    REQUIRE(back.points.size() == g.mesh.points.size());
    REQUIRE(back.tets == g.mesh.tets);
    for (std::size_t i = 0; i < back.points.size(); ++i) {
      CHECK(back.points[i] == g.mesh.points[i]);  // bit-exact: 17 digits / raw doubles
      CHECK(back.scalars[i] == g.mesh.scalars[i]);
    }
  }
}

TEST_CASE("VTK legacy reader: extra arrays, named scalars, CELL_DATA, version 5.1 layout", "[mesh]") {
  const std::string base = kOneTetAscii;
  SECTION("a plain ASCII file") {
    const TetMesh m = parse_vtk_legacy(base, "m.vtk");
    CHECK(m.points.size() == 4);
    CHECK(m.scalars[3] == 3.5);
  }
  SECTION("arrays before and after the wanted one are skipped; scalar_name picks one") {
    const std::string v = std::string(base) +
                          "VECTORS vel float\n1 0 0 1 0 0 1 0 0 1 0 0\n"
                          "SCALARS other int 1\nLOOKUP_TABLE default\n7 8 9 10\n"
                          "FIELD fd 1\nextra 2 4 double\n1 2 3 4 5 6 7 8\n"
                          "CELL_DATA 1\nSCALARS cs float 1\nLOOKUP_TABLE default\n4\n";
    CHECK(parse_vtk_legacy(v, "m.vtk").scalars[0] == 0.5);
    CHECK(parse_vtk_legacy(v, "m.vtk", {"other"}).scalars[0] == 7.0);
  }
  SECTION("version 5.1: OFFSETS and CONNECTIVITY") {
    std::string v = replace(base, "Version 3.0", "Version 5.1");
    v = replace(v, "CELLS 1 5\n4 0 1 2 3\n",
                "CELLS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2 3\n");
    const TetMesh m = parse_vtk_legacy(v, "m.vtk");
    CHECK(m.tets.size() == 1);
    CHECK(m.tets[0] == std::array<std::int32_t, 4>{0, 1, 2, 3});
  }
}

TEST_CASE("VTK legacy reader: every problem is one line naming the file and section", "[mesh]") {
  const std::string base = kOneTetAscii;
  const test::BadText bad[] = {
      {replace(base, "# vtk DataFile", "# vtx DataFile"), "m.vtk: header: not a VTK legacy file"},
      {replace(base, "UNSTRUCTURED_GRID", "STRUCTURED_POINTS"), "m.vtk: DATASET: STRUCTURED_POINTS is image data, not a mesh"},
      {replace(base, "CELL_TYPES 1\n10", "CELL_TYPES 1\n12"), "m.vtk: CELL_TYPES[0]: cell type hexahedron (VTK id 12): the tetrahedral path integrates only tetrahedra; integrate this file with --cells split (VTK's tetrahedralisation, an approximation of the cell's own interpolation)"},
      {replace(base, "0 0 0  1 0 0", "0 0 nan  1 0 0"), "m.vtk: POINTS[0][2]: coordinate must be finite, got nan"},
      {replace(base, "4 0 1 2 3", "4 0 1 2 9"), "m.vtk: CELLS[0][3]: point index 9 out of range [0, 4)"},
      {replace(base, "POINT_DATA 4", "POINT_DATA 3"), "m.vtk: POINT_DATA: 3 scalars for 4 points"},
      {replace(base, "SCALARS s double 1\nLOOKUP_TABLE default\n0.5 1.5 2.5 3.5\n", ""), "m.vtk: POINT_DATA: no field to integrate: no one-component point or cell array that is not a region marker (arrays: none)"},
      {replace(base, "0.5 1.5 2.5 3.5\n", "0.5 1.5\n"), "m.vtk: POINT_DATA: expected 4 values, file ends after 2"},
      {replace(base, "0.5 1.5", "0.5 x1.5"), "m.vtk: POINT_DATA[1]: not a number: 'x1.5'"},
      {replace(base, "CELLS 1 5\n", "CELLS 1 6\n"), "m.vtk: CELLS[5]: not a number: 'CELL_TYPES'"},
      {replace(base, "CELL_TYPES 1\n10\n", ""), "m.vtk: CELL_TYPES: missing"},
      {replace(base, "POINTS 4 float", "POINTS 4 quaternion"), "m.vtk: POINTS: unknown data type 'quaternion'"},
  };
  test::check_refusal_table(bad, [](const test::BadText& b) { return error_of(b.text); });
  SECTION("strict (--strict-mesh): inverted and degenerate tets are refused by validate_tet_mesh") {
    const test::BadText strict[] = {
        {replace(base, "4 0 1 2 3", "4 0 1 3 2"), "m.vtk: CELLS[0]: inverted tetrahedron"},
        {replace(base, "4 0 1 2 3", "4 0 1 2 2"), "m.vtk: CELLS[0]: degenerate tetrahedron: point 2 appears twice"},
        {replace(base, "0 0 1\n", "1 1 0\n"), "m.vtk: CELLS[0]: degenerate tetrahedron (volume 0"},
    };
    for (const test::BadText& b : strict) {
      INFO(b.expect);
      const TetMesh m = parse_vtk_legacy(b.text, "m.vtk");  // the reader checks structure only
      std::string msg = "(no error)";
      try {
        validate_tet_mesh(m, "m.vtk", MeshFieldNames{"POINTS", "POINT_DATA", "CELLS"});
      } catch (const InputError& e) {
        msg = e.what();
      }
      CHECK(msg.rfind(b.expect, 0) == 0);
    }
  }
  SECTION("truncated binary data") {
    const GeneratedMesh g = generate_mesh("ball", 1, 1);
    const std::string bin = encode_vtk_legacy(g.mesh, VtkWriteOptions{});
    const std::string msg = error_of(bin.substr(0, bin.size() / 2));
    CHECK(msg.rfind("m.vtk: CELLS: binary data truncated", 0) == 0);
  }
  SECTION("truncated binary POINTS say how many values the file has") {
    const GeneratedMesh g = generate_mesh("ball", 1, 1);
    const std::string bin = encode_vtk_legacy(g.mesh, VtkWriteOptions{});
    const std::size_t at = bin.find("POINTS ");
    REQUIRE(at != std::string::npos);
    const std::size_t eol = bin.find('\n', at);
    std::istringstream header(bin.substr(at, eol - at));
    std::string word, type;
    std::size_t n = 0;
    header >> word >> n >> type;
    REQUIRE((type == "double" || type == "float"));
    const std::size_t width = type == "double" ? 8 : 4;
    // Ten whole values and three bytes of the eleventh.
    const std::string msg = error_of(bin.substr(0, eol + 1 + 10 * width + 3));
    CHECK(msg == "m.vtk: POINTS: binary data truncated: need " + std::to_string(3 * n) + " " + type +
                     " values, file has 10");
  }
}

TEST_CASE("Mesh topology errors: a face in three tets, overlapping tets", "[mesh]") {
  TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0.2, 0.2, 2)};
  m.scalars.assign(6, 0.0);
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  validate_tet_mesh(m, "m");
  CHECK_NOTHROW(TetTraversal(m, "m"));
  m.tets.push_back({0, 1, 2, 5});  // a third tet on face (0, 1, 2), overlapping the first
  validate_tet_mesh(m, "m");
  CHECK_THROWS_WITH(TetTraversal(m, "m"), Catch::StartsWith("m: tets[2]: face (0, 1, 2) is shared by more than two tetrahedra"));
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 5}};
  CHECK_THROWS_WITH(TetTraversal(m, "m"), Catch::StartsWith("m: tets[1]: overlaps tets[0]"));
}

TEST_CASE("Inline JSON mesh cases: every field error names the file and field", "[mesh]") {
  const std::string good = R"({"name": "x", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "scalars": [0, 1, 2, 3], "tets": [[0,1,2,3]]},
    "rays": [{"origin": [0.2, 0.2, 5], "direction": [0, 0, -1]}]})";
  const auto err = [](const std::string& text) {
    return test::input_error_of([&] { parse_case_text(text, "c.json", MeshReadOptions{true}); });
  };
  const Case c = parse_case_text(good, "c.json", MeshReadOptions{true});
  REQUIRE(c.rays.size() == 1);
  REQUIRE(c.rays[0].segments.size() == 1);
  CHECK(c.rays[0].segments[0].length == Approx(0.6).epsilon(1e-15));
  struct Bad {
    std::string from, to, expect;
  };
  const Bad bad[] = {
      {"[[0,1,2,3]]", "[[0,1,2,4]]", "c.json: mesh.tets[0][3]: point index 4 out of range [0, 4)"},
      {"[[0,1,2,3]]", "[[0,1,3,2]]", "c.json: mesh.tets[0]: inverted tetrahedron"},
      {"[[0,1,2,3]]", "[[0,1,2]]", "c.json: mesh.tets[0]: must be [i, j, k, l] point indices"},
      {"[[0,1,2,3]]", "[[0,1,2,1.5]]", "c.json: mesh.tets[0][3]:"},
      {"[0, 1, 2, 3]", "[0, 1, 2]", "c.json: mesh.scalars: 3 scalars for 4 points"},
      {"[[0,0,0],", "[[0,0,\"a\"],", "c.json: mesh.points[0][2]:"},
      {"\"tets\"", "\"cells\"", "c.json: mesh.cells: unknown field"},
      {"\"mesh\": {", "\"mesh_file\": \"none.vtk\", \"mesh\": {", "c.json: (root): give exactly one of \"mesh\" (inline) or \"mesh_file\""},
      {"\"rays\": [{\"origin\": [0.2, 0.2, 5], \"direction\": [0, 0, -1]}]", "\"rays\": [{\"origin\": [0.2, 0.2, 5], \"direction\": [0, 0, 0]}]", "c.json: rays[0].direction:"},
      {"\"rays\": [{\"origin\": [0.2, 0.2, 5], \"direction\": [0, 0, -1]}]", "\"background\": [0, 0, 0]", "c.json: (root): a mesh case needs \"rays\" or a \"camera\""},
  };
  for (const Bad& b : bad) {
    INFO(b.expect);
    const std::string msg = err(replace(good, b.from, b.to));
    CHECK(msg.rfind(b.expect, 0) == 0);
  }
  CHECK(err(replace(good, "\"mesh\": {\"points\": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], \"scalars\": [0, 1, 2, 3], \"tets\": [[0,1,2,3]]}",
                    "\"mesh_file\": \"missing.vtk\""))
            .rfind("c.json: mesh_file: no such file: missing.vtk", 0) == 0);
}
