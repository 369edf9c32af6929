// test_vtk_mesh_reader.cpp -- .vtu meshes through VTK's XML reader (src/rayint/vtk/), built only
// with -DRAYINT_WITH_VTK=ON: the same mesh written as .vtu reads to the same TetMesh as rayint's
// own .vtk reader, a mesh case with a .vtu gives the same numbers as with the .vtk, and bad .vtu
// input (unreadable, non-tet cells) exits 2 with one stderr line naming the file and the field.
#include <catch2/catch.hpp>

#include <fstream>

#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "../test_paths.hpp"
#include "../cli_harness.hpp"
#include "../cli_refusal.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/vtk/vtk_mesh_reader.hpp"

using namespace rayint;
using rayint::test::run_cli;
using rayint::test::TempDir;
namespace fs = std::filesystem;

namespace {

const std::string kMeshField = "\"mesh_file\": \"meshes/linear-box.vtk\"";
const std::string kMeshFieldVtu = "\"mesh_file\": \"meshes/linear-box.vtu\"";
const fs::path kBox = fs::path(RAYINT_SOURCE_DIR) / "cases" / "meshes" / "linear-box.vtk";

void write_vtu(vtkUnstructuredGrid* grid, const fs::path& out) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(out.string().c_str());
  writer->SetInputData(grid);
  writer->SetDataModeToBinary();
  REQUIRE(writer->Write() == 1);
}

void box_as_vtu(const fs::path& out) {
  vtkNew<vtkUnstructuredGridReader> reader;  // VTK's legacy reader, independent of rayint's
  reader->SetFileName(kBox.string().c_str());
  reader->Update();
  write_vtu(reader->GetOutput(), out);
}

// cases/mesh-linear-field.json with its mesh read from meshes/linear-box.vtu, as `name` in `dir`.
void write_vtu_case(const TempDir& dir, const std::string& name) {
  std::ifstream in(fs::path(RAYINT_SOURCE_DIR) / "cases" / "mesh-linear-field.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find(kMeshField), kMeshField.size(), kMeshFieldVtu);
  dir.write(name, text);
}

}  // namespace

TEST_CASE(".vtu reads to the same TetMesh as rayint's .vtk reader", "[vtk][mesh]") {
  TempDir dir;
  box_as_vtu(dir.path / "box.vtu");
  const TetMesh want = read_vtk_legacy(kBox.string());
  const TetMesh got = read_vtk_unstructured_grid((dir.path / "box.vtu").string(), "");
  REQUIRE(got.points.size() == want.points.size());
  REQUIRE(got.tets.size() == want.tets.size());
  for (std::size_t i = 0; i < want.points.size(); ++i) {
    CHECK(got.points[i] == want.points[i]);
    CHECK(got.scalars[i] == want.scalars[i]);
  }
  for (std::size_t i = 0; i < want.tets.size(); ++i) CHECK(got.tets[i] == want.tets[i]);
}

TEST_CASE("a mesh case with a .vtu gives the .vtk case's numbers", "[vtk][mesh][cli]") {
  TempDir dir;
  fs::create_directories(dir.path / "meshes");
  box_as_vtu(dir.path / "meshes" / "linear-box.vtu");
  fs::copy_file(kBox, dir.path / "meshes" / "linear-box.vtk");
  std::ifstream in(fs::path(RAYINT_SOURCE_DIR) / "cases" / "mesh-linear-field.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string vtu = text;
  vtu.replace(vtu.find(kMeshField), kMeshField.size(), kMeshFieldVtu);
  REQUIRE(vtu.find(kMeshFieldVtu) != std::string::npos);
  dir.write("a.json", text);
  dir.write("b.json", vtu);
  const auto a = run_cli(dir.path, "eval a.json --methods exact,vtk_linear --format table");
  const auto b = run_cli(dir.path, "eval b.json --methods exact,vtk_linear --format table");
  INFO(a.err << b.err);
  REQUIRE(a.status == 0);
  REQUIRE(b.status == 0);
  const auto body = [](const std::string& s) { return s.substr(0, s.find("time/ray")); };
  CHECK(body(a.out) == body(b.out));
  // the per-ray numbers (max rel, max ulp columns) agree; timing columns differ by run
  const auto numbers = [](const std::string& s) {
    std::string out;
    std::istringstream lines_in(s);
    for (std::string line; std::getline(lines_in, line);) out += line.substr(0, std::min<std::size_t>(line.size(), 90)) + "\n";
    return out;
  };
  CHECK(numbers(a.out) == numbers(b.out));
}

TEST_CASE("bad .vtu: unreadable file, exit 2 with one line naming the file", "[vtk][mesh][cli][bad_input]") {
  TempDir dir;
  fs::create_directories(dir.path / "meshes");
  dir.write("meshes/linear-box.vtu", "this is not a VTK XML file\n");
  write_vtu_case(dir, "c.json");
  // check_refused: exit 2, one stderr line, nothing written (no out.json)
  CHECK(test::check_refused(dir, "eval c.json -o out.json").err.find("linear-box.vtu: file:") != std::string::npos);
}

TEST_CASE("bad .vtu: a hexahedron, exit 2 with one line naming the file and the cell", "[vtk][mesh][cli][bad_input]") {
  TempDir dir;
  fs::create_directories(dir.path / "meshes");
  vtkNew<vtkPoints> pts;
  vtkNew<vtkDoubleArray> s;
  s->SetName("s");
  for (int k = 0; k < 8; ++k) {
    pts->InsertNextPoint(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    s->InsertNextValue(0.1 * k);
  }
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(pts);
  grid->GetPointData()->SetScalars(s);
  const vtkIdType hex[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
  write_vtu(grid, dir.path / "meshes" / "linear-box.vtu");
  write_vtu_case(dir, "d.json");
  CHECK(test::check_refused(dir, "eval d.json -o out.json").err.find("linear-box.vtu: Cells[0]: cell type 12") !=
        std::string::npos);
}
