#pragma once
// The bow-tie hexahedron the own-mode CLI tests run (tests/test_cell_traversal.cpp,
// tests/test_own_mode_cli.cpp): VTK's node order with the top face's nodes 6 and 7 swapped, so
// Newton cannot locate points in it and rays through it fail in the own mode.
#include <nlohmann/json.hpp>
#include <string>

#include "cli_harness.hpp"

namespace rayint::test {

// Writes bow.vtk and bow.json (a `pixels` x `pixels` camera looking at the cell) into `dir`, runs
// `rayint eval bow.json --no-reference` there and returns its JSON, after requiring what makes
// the fixture useful: exit 1 and some failed rays (cases[0].failed > 0).
inline nlohmann::json eval_bow_tie(const TempDir& dir, int pixels) {
  dir.write("bow.vtk",
            "# vtk DataFile Version 3.0\nh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
            "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 7 6\n"
            "CELL_TYPES 1\n12\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n");
  const std::string n = std::to_string(pixels);
  dir.write("bow.json", R"({"name": "bow", "transfer_function": {"density": [[0, 1], [7, 2]], "color": [[0, 1]]},
    "mesh_file": "bow.vtk", "camera": {"position": [0.5, 0.3, 4], "look_at": [0.5, 0.5, 0.5], "fov_deg": 40, "width": )" +
                            n + R"(, "height": )" + n + "}}");
  const CliRun e = run_cli(dir.path, "eval bow.json -q --no-reference");
  INFO(e.err);
  REQUIRE(e.status == 1);
  nlohmann::json j = nlohmann::json::parse(e.out);
  REQUIRE(j["cases"][0]["failed"].get<long>() > 0);
  return j;
}

}  // namespace rayint::test
