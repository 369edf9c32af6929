// Parallel structured grids (.pvts, .pvtr; input/vtk_xml_reader.hpp) as VTK 9.1's
// vtkXMLPStructuredGridWriter / vtkXMLPRectilinearGridWriter write them
// (tests/fixtures/readers/parallel/, generate_parallel.py): read as one structured mesh equal to
// the serial .vts / .vtr they were written from, with and without ghost levels; bad files are one
// line naming the file and the field, exit 2 from the CLI (tag [readers][parallel]).
#include <catch2/catch.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "test_paths.hpp"
#include "cli_harness.hpp"
#include "input_text.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"
#include "rayint/mesh/cell_mesh.hpp"

using namespace rayint;
using rayint::test::TempDir;

namespace {

const std::string kReaders = RAYINT_SOURCE_DIR + "/tests/fixtures/readers/";
const std::string kParallel = kReaders + "parallel/";

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Equal as data: the same points (bitwise), cells (types and connectivity), point and cell
// scalars, structured dimensions.
void require_same_mesh(const CellMesh& a, const CellMesh& b) {
  REQUIRE(a.points.size() == b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) REQUIRE(a.points[i] == b.points[i]);
  CHECK(a.types == b.types);
  CHECK(a.offsets == b.offsets);
  CHECK(a.connectivity == b.connectivity);
  CHECK(a.scalars == b.scalars);
  CHECK(a.cell_scalars == b.cell_scalars);
  REQUIRE(a.structured.has_value());
  REQUIRE(b.structured.has_value());
  CHECK(*a.structured == *b.structured);
  CHECK(a.info.ghost_cells == 0);
}

// Copies a parallel fixture and its pieces into `dir`, the .p* text passed through `edit`.
std::string copy_parallel(const TempDir& dir, const std::string& name, const std::string& piece_glob_stem,
                          int pieces, const std::string& piece_ext,
                          const std::function<std::string(std::string)>& edit = nullptr) {
  std::string text = text_of(kParallel + name);
  if (edit) text = edit(text);
  dir.write(name, text);
  for (int k = 0; k < pieces; ++k) {
    const std::string piece = piece_glob_stem + "_" + std::to_string(k) + piece_ext;
    dir.write(piece, text_of(kParallel + piece));
  }
  return (dir.path / name).string();
}

std::string refusal(const std::string& path) {
  return test::input_error_of([&] { read_cell_mesh_file(path); });
}

}  // namespace

TEST_CASE("parallel structured grids written by VTK read as the serial grid they were written from", "[readers][parallel]") {
  std::ifstream in(kParallel + "parallel-expected.json");
  REQUIRE(in.good());
  const nlohmann::json want = nlohmann::json::parse(in);
  int files = 0;
  for (const auto& [name, e] : want.at("files").items()) {
    INFO(name);
    // VTK's own parallel reader gave back the serial grid (recorded by the generator).
    REQUIRE(e.at("vtk_equals_serial").get<bool>());
    const CellMesh parallel = read_cell_mesh_file(kParallel + name);
    const CellMesh serial = read_cell_mesh_file(kReaders + e.at("serial").get<std::string>());
    CHECK(static_cast<long>(parallel.points.size()) == e.at("vtk_points").get<long>());
    CHECK(static_cast<long>(parallel.cell_count()) == e.at("vtk_cells").get<long>());
    require_same_mesh(parallel, serial);
    // The cell array too (cellid: 0..23 in VTK's cell order), when asked for by name.
    if (name.find("twisted") != std::string::npos) {
      const CellMesh ids = read_cell_mesh_file(kParallel + name, {"cellid"});
      REQUIRE(ids.cell_scalars.size() == ids.cell_count());
      for (std::size_t c = 0; c < ids.cell_count(); ++c) CHECK(ids.cell_scalars[c] == static_cast<double>(c));
    }
    ++files;
  }
  CHECK(files == 4);
}

TEST_CASE("parallel structured grids: bad files are one line naming the file and the field", "[readers][parallel]") {
  TempDir dir;
  // A piece file missing.
  {
    const std::string p = copy_parallel(dir, "twisted-3.pvts", "twisted-3", 2, ".vts");
    const std::string why = refusal(p);
    INFO(why);
    CHECK(why.rfind(p + ": PStructuredGrid/Piece: the piece ", 0) == 0);
    CHECK(why.find("twisted-3_2.vts does not exist") != std::string::npos);
  }
  // A piece that the parallel file places elsewhere than the piece says.
  {
    const std::string p = copy_parallel(dir, "twisted-3.pvts", "twisted-3", 3, ".vts", [](std::string t) {
      return std::regex_replace(t, std::regex("Extent=\"0 1 0 3 0 2\""), "Extent=\"1 2 0 3 0 2\"", std::regex_constants::format_first_only);
    });
    const std::string why = refusal(p);
    INFO(why);
    CHECK(why.find("twisted-3_0.vts: StructuredGrid/Piece: Extent differs from the one") != std::string::npos);
  }
  // Pieces that leave cells uncovered (the last piece dropped from the list).
  {
    const std::string p = copy_parallel(dir, "odd-2.pvtr", "odd-2", 2, ".vtr", [](std::string t) {
      return std::regex_replace(t, std::regex("<Piece[^>]*odd-2_1.vtr\"/>"), "");
    });
    const std::string why = refusal(p);
    INFO(why);
    CHECK(why.rfind(p + ": PRectilinearGrid: the pieces do not cover the WholeExtent", 0) == 0);
  }
  // A WholeExtent larger than the pieces.
  {
    const std::string p = copy_parallel(dir, "odd-2.pvtr", "odd-2", 2, ".vtr", [](std::string t) {
      return std::regex_replace(t, std::regex("WholeExtent=\"0 3 0 2 0 2\""), "WholeExtent=\"0 3 0 2 0 3\"");
    });
    const std::string why = refusal(p);
    INFO(why);
    CHECK(why.rfind(p + ": PRectilinearGrid: the pieces do not cover the WholeExtent", 0) == 0);
  }
  // The CLI: one line, exit 2, nothing written.
  {
    TempDir run;
    copy_parallel(run, "twisted-3.pvts", "twisted-3", 2, ".vts");
    const auto before = run.entries();
    const auto r = rayint::test::run_cli(run.path, "mesh info twisted-3.pvts");
    CHECK(r.status == 2);
    CHECK(rayint::test::line_count(r.err) == 1);
    CHECK(r.err.find("twisted-3.pvts: PStructuredGrid/Piece: the piece ") != std::string::npos);
    CHECK(run.entries() == before);
  }
}

TEST_CASE("parallel structured grids: pieces that disagree on a shared point are refused", "[readers][parallel]") {
  TempDir dir;
  // Two pieces of odd-ghost.pvtr overlap (ghost level 1); change one coordinate in one of them.
  const std::string p = copy_parallel(dir, "odd-ghost.pvtr", "odd-ghost", 3, ".vtr");
  std::string piece = text_of(kParallel + "odd-ghost_1.vtr");
  const std::size_t at = piece.find("<Coordinates>");
  REQUIRE(at != std::string::npos);
  const std::size_t values = piece.find('>', piece.find("<DataArray", at)) + 1;
  const std::size_t space = piece.find_first_not_of(" \n", values);
  piece.insert(space, "-7");  // the first x coordinate becomes -7<old digits>
  dir.write("odd-ghost_1.vtr", piece);
  const std::string why = refusal(p);
  INFO(why);
  CHECK(why.find("odd-ghost_1.vtr: RectilinearGrid/Piece/Coordinates/DataArray[0]: coordinate 0 differs") != std::string::npos);
}
