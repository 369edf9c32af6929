// Mesh cases through the real rayint binary (tag [mesh]): eval gives per-ray JSON, render writes
// the image, the heat map and the statistics, generate-mesh writes a readable file; bad input
// exits 2 with one line naming the file and field and leaves no output file behind.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <string>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"

using rayint::test::run_cli;
using rayint::test::run_cli_ok;
using rayint::test::slurp;
using rayint::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kMeshCase = R"({
  "name": "tiny",
  "transfer_function": {"density": [[0, 1], [1, 3]], "color": [[0, 0.5], [1, 1]]},
  "mesh": {"points": [[0,0,0],[1,0,0],[0,1,0],[0,0,1],[1,1,1]], "scalars": [0, 1, 0.5, 0.2, 0.9],
           "tets": [[0,1,2,3],[1,2,3,4]]},
  "background": [0.1, 0.2, 0.3],
  "rays": [{"origin": [0.2, 0.2, 5], "direction": [0, 0, -1]},
           {"origin": [5, 5, 5], "direction": [0, 0, 1]}],
  "camera": {"position": [0.3, 0.3, 4], "look_at": [0.3, 0.3, 0], "fov_deg": 30, "width": 12, "height": 10}
})";

std::string with(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

void expect_bad(const TempDir& dir, const std::string& args, const std::string& prefix) {
  const auto before = dir.entries();
  const auto r = run_cli(dir.path, args);
  INFO(args << "\nstderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("rayint: error: " + prefix, 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(dir.entries() == before);
}

}  // namespace

TEST_CASE("CLI: eval on a mesh case gives per-ray JSON, a missing ray only the background", "[mesh]") {
  TempDir dir;
  dir.write("tiny.json", kMeshCase);
  const auto r = run_cli_ok(dir.path, "eval tiny.json --methods exact --no-timing");
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["cases"].size() == 1);
  const auto& rays = j["cases"][0]["rays"];
  REQUIRE(rays.size() == 2);
  CHECK(rays[0]["methods"]["exact"]["rel_error"][0].get<double>() < 1e-13);
  // The second ray misses: intensity = background, transmittance 1.
  CHECK(rays[1]["methods"]["exact"]["intensity"][2].get<double>() == 0.3);
  CHECK(rays[1]["methods"]["exact"]["transmittance"][0].get<double>() == 1.0);
}

TEST_CASE("CLI: eval on a mesh case with only a camera evaluates one ray per pixel", "[mesh]") {
  TempDir dir;
  std::string c = with(kMeshCase, R"("rays": [{"origin": [0.2, 0.2, 5], "direction": [0, 0, -1]},
           {"origin": [5, 5, 5], "direction": [0, 0, 1]}],)", "");
  c = with(c, R"("width": 12, "height": 10)", R"("width": 3, "height": 2)");
  dir.write("cam.json", c);
  const auto r = run_cli_ok(dir.path, "eval cam.json --methods exact --no-timing");
  CHECK(nlohmann::json::parse(r.out)["cases"][0]["rays"].size() == 6);
}

TEST_CASE("CLI: eval on the bundled mesh cases (mesh_file relative to the case)", "[mesh]") {
  const auto r = run_cli_ok(fs::path(RAYINT_SOURCE_DIR), "eval cases/mesh-ring-nonconvex.json --methods exact --no-timing");
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["cases"][0]["rays"].size() == 5);
}

TEST_CASE("CLI: render a mesh case with --compare and --stats", "[mesh]") {
  TempDir dir;
  dir.write("tiny.json", kMeshCase);
  const auto r = run_cli_ok(dir.path, "render tiny.json -o img.png --compare riemann:n=8 --stats s.json --threads 2");
  CHECK(fs::file_size(dir.path / "img.png") > 0);
  CHECK(fs::file_size(dir.path / "img.error.png") > 0);
  const auto s = nlohmann::json::parse(slurp(dir.path / "s.json"));
  CHECK(s["cost"]["rays"] == 120);
  CHECK(s["compare"]["method"] == "riemann:n=8");
  CHECK(s["compare"]["max_rel_error"].get<double>() > 0.0);
  CHECK(r.err.find("rows") != std::string::npos);  // progress
}

TEST_CASE("CLI: generate-mesh writes a VTK file the reader accepts", "[mesh]") {
  TempDir dir;
  run_cli_ok(dir.path, "generate-mesh ring --n 1 -o ring.vtk --ascii");
  const rayint::TetMesh m = rayint::read_vtk_legacy((dir.path / "ring.vtk").string());
  CHECK(m.tets.size() == 504);  // (100 - 16) cubes x 6
  expect_bad(dir, "generate-mesh torus -o t.vtk", "kind: torus not in");
}

TEST_CASE("CLI: bad mesh input exits 2 with one line and no output", "[mesh]") {
  TempDir dir;
  dir.write("oob.json", with(kMeshCase, "[1,2,3,4]]", "[1,2,3,9]]"));
  expect_bad(dir, "eval oob.json -o out.json", "oob.json: mesh.tets[1][3]: point index 9 out of range [0, 5)");
  expect_bad(dir, "render oob.json -o out.png", "oob.json: mesh.tets[1][3]: point index 9 out of range");
  dir.write("inv.json", with(kMeshCase, "[0,1,2,3]", "[0,2,1,3]"));
  expect_bad(dir, "eval --strict-mesh inv.json -o out.json", "inv.json: mesh.tets[0]: inverted tetrahedron");
  expect_bad(dir, "render --strict-mesh inv.json -o out.png", "inv.json: mesh.tets[0]: inverted tetrahedron");
  dir.write("count.json", with(kMeshCase, "0.2, 0.9]", "0.2]"));
  expect_bad(dir, "eval count.json -o out.json", "count.json: mesh.scalars: 4 scalars for 5 points");
  dir.write("nofile.json", with(kMeshCase, R"("mesh": {"points")", R"("mesh_file": "gone.vtk", "x": {"points")"));
  expect_bad(dir, "eval nofile.json -o out.json", "nofile.json: x: unknown field");
  dir.write("gone.json", R"({"name": "g", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh_file": "gone.vtk", "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  expect_bad(dir, "eval gone.json -o out.json", "gone.json: mesh_file: no such file");
  dir.write("m.obj", "v 0 0 0\n");
  dir.write("obj.json", R"({"name": "o", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh_file": "m.obj", "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  expect_bad(dir, "eval obj.json -o out.json", "obj.json: mesh_file: unsupported mesh format \".obj\"");
  dir.write("hex.vtk", "# vtk DataFile Version 3.0\nh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
                       "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 6 7\n"
                       "CELL_TYPES 1\n12\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n");
  dir.write("hex.json", R"({"name": "h", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "mesh_file": "hex.vtk", "rays": [{"origin": [0, 0, 5], "direction": [0, 0, -1]}]})");
  // A hexahedron is integrated in its own interpolation ("mode": "own"); the segment methods do
  // not apply there, and commands that need segments name --cells split.
  expect_bad(dir, "eval hex.json --methods exact -o out.json", "hex.json: --methods: the own interpolation of cells other than tetrahedra is one method");
  // bench times them in their own interpolation against VTK's split (tests/test_own_mode_cli.cpp),
  // but not in shards.
  expect_bad(dir, "bench hex.json --shard 0/2 -o part.json", "hex.json: mesh_file: cells other than tetrahedra (own interpolation vs split timing) cannot be sharded");
  // Surface shading is not simulated in the own mode: every command refuses it rather than
  // integrating the case without it (eval did, exit 0).
  dir.write("hexshade.json", R"({"name": "h", "transfer_function": {"density": [[0, 1]], "color": [[0, 1]]},
    "shading": {"surfaces": [[0.4, 0.5]]}, "mesh_file": "hex.vtk",
    "camera": {"position": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0.5], "fov_deg": 30, "width": 4, "height": 4}})");
  const std::string shade = "hexshade.json: shading: not available in the own mode of cells other than tetrahedra";
  expect_bad(dir, "eval hexshade.json -o out.json", shade);
  expect_bad(dir, "render hexshade.json -o out.npy", shade);
  expect_bad(dir, "check hexshade.json --candidate-image nosuch.npy -o out.json", shade);
  expect_bad(dir, "check hexshade.json --candidate nosuch.json -o out.json", shade);
  // grad has no --cells option: the line must not tell its user to pass one to it.
  expect_bad(dir, "grad hex.json -o out.json", "hex.json: mesh_file: hex.vtk holds cells other than tetrahedra: this command needs linear segments, which their own interpolation does not give (rayint eval, render and check integrate them in it, bench times that against VTK's split; eval, render, check and bench take VTK's tetrahedralisation of them with --cells split)");
  dir.write("nocam.json", with(kMeshCase, R"("camera": {"position": [0.3, 0.3, 4], "look_at": [0.3, 0.3, 0], "fov_deg": 30, "width": 12, "height": 10})", R"("description": "")"));
  expect_bad(dir, "render nocam.json -o out.png", "nocam.json: camera: required to render a mesh case");
  dir.write("tiny.json", kMeshCase);
  expect_bad(dir, "render tiny.json -o out.png --compare nosuch", "");
  dir.write("shade.json", with(kMeshCase, R"("background")", R"("shading": {"surfaces": [[0.5, 0.4]]}, "background")"));
  expect_bad(dir, "eval shade.json -o out.json", "shade.json: shading.surfaces[0]: need lo < hi");
}
