// Inputs the libFuzzer targets of fuzz/ found to crash, hang or leak (README, "Fuzzing"), each
// kept as a regression test with the input the fuzzer wrote (tests/data/fuzz/) or a minimal
// inline equivalent.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "test_paths.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/gmsh_reader.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/render/float_image.hpp"

using namespace rayint;
using Catch::Matchers::Contains;

namespace {

std::string read_fuzz_input(const std::string& name) {
  std::ifstream in(std::string(RAYINT_SOURCE_DIR) + "/tests/data/fuzz/" + name, std::ios::binary);
  REQUIRE(in.good());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// One positively oriented tet with corner length `a`, as VTK legacy ASCII.
std::string one_tet(const std::string& a) {
  return "# vtk DataFile Version 3.0\nbig\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
         "0 0 0  " + a + " 0 0  0 " + a + " 0  0 0 " + a + "\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n"
         "POINT_DATA 4\nSCALARS s double 1\nLOOKUP_TABLE default\n0 1 2 3\n";
}

}  // namespace

// gmsh_fuzzer and vtk_legacy_fuzzer, 2026-12-03: a mesh with a point at 3.96e252 (gmsh, binary
// MSH 2.2) or 1.68e306 (VTK legacy, binary) was accepted, and the first ray traced through it
// handed Embree a single-precision ray with an infinite origin: Embree's assertion ray.valid()
// aborted the process. TetTraversal now refuses coordinates beyond +-1e18 with one line.
TEST_CASE("fuzz regression: mesh points beyond +-1e18 are refused before Embree sees them", "[mesh][fuzz]") {
  struct Input {
    std::string file;
    TetMesh (*parse)(std::string_view, const std::string&, const ScalarChoice&);
  };
  for (const Input& in : {Input{"gmsh-huge-coordinate.msh", &parse_gmsh},
                          Input{"vtk-legacy-huge-coordinate.vtk", &parse_vtk_legacy}}) {
    INFO(in.file);
    TetMesh mesh = in.parse(read_fuzz_input(in.file), in.file, {});
    REQUIRE_NOTHROW(repair_tet_mesh(mesh, in.file));
    CHECK_THROWS_WITH(TetTraversal(mesh, in.file),
                      Contains(in.file + ": points[") && Contains("beyond +-1e18"));
  }
  TetMesh huge = parse_vtk_legacy(one_tet("1e300"), "big.vtk");
  CHECK_THROWS_WITH(TetTraversal(huge, "big.vtk"),
                    Contains("big.vtk: points[1][0]: coordinate 1e+300 beyond +-1e18"));
  // At the limit the mesh is accepted (whether single precision traces it well there is another
  // matter); the same tet at scale 1 is traced through its inside.
  TetMesh edge = parse_vtk_legacy(one_tet("1e18"), "edge.vtk");
  CHECK_NOTHROW(TetTraversal(edge, "edge.vtk"));
  TetMesh unit = parse_vtk_legacy(one_tet("1"), "unit.vtk");
  const TetTraversal traversal(unit, "unit.vtk");
  RayTrace trace;
  traversal.trace(ViewRay{Vec3(0.2, 0.2, -0.5), Vec3(0, 0, 1)}, trace);
  REQUIRE(trace.crossings.size() == 1);
  CHECK(trace.crossings[0].t_out > trace.crossings[0].t_in);
}

// exr_reader_fuzzer, 2026-12-03: a 663-byte EXR (a mutated oiiotool file) whose header declares
// an attribute of about 1.6 GB made OpenEXR allocate it before reading: 1.2 GB of memory and 23 s
// under ASan, a timeout. decode_exr now checks every attribute size against the bytes left first.
TEST_CASE("fuzz regression: an EXR attribute larger than the file is refused before OpenEXR reads it", "[image][fuzz]") {
  const std::string bytes = read_fuzz_input("exr-huge-attribute.exr");
  REQUIRE(bytes.size() == 663);
  CHECK_THROWS_WITH(decode_exr(bytes, "huge.exr"),
                    Contains("huge.exr: exr: header: an attribute declares") && Contains("the file has"));
  // A truncated header and an unterminated name are one line too.
  CHECK_THROWS_WITH(decode_exr(bytes.substr(0, 6), "short.exr"), Contains("short.exr: exr: truncated header"));
  CHECK_THROWS_WITH(decode_exr(bytes.substr(0, 8) + std::string(300, 'a'), "name.exr"),
                    Contains("name.exr: exr: header: attribute name not terminated"));
}
