// test_vtk_xml_oracle.cpp -- VTK's own XML readers as the oracle of rayint's (input/vtk_xml_reader),
// built only with -DRAYINT_WITH_VTK=ON: every fixture in tests/fixtures/vtkxml/ (written by VTK
// and meshio in every data mode, encoding, compressor, header type, byte order and id type) read
// by vtkXMLUnstructuredGridReader / vtkXMLImageDataReader in this process and by rayint's readers
// gives the same points, tetrahedra, point arrays and image geometry, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <type_traits>

#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "../test_paths.hpp"
#include "rayint/input/vtk_xml_reader.hpp"

using namespace rayint;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(RAYINT_SOURCE_DIR) / "tests" / "fixtures" / "vtkxml";

// What VTK's reader `Reader` makes of `file`, which it must read without error (the data set
// outlives the reader).
template <class Reader>
auto vtk_read(const fs::path& file) {
  vtkNew<Reader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  REQUIRE(reader->GetErrorCode() == 0);
  return vtkSmartPointer<std::remove_pointer_t<decltype(reader->GetOutput())>>(reader->GetOutput());
}

std::vector<fs::path> fixtures(const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("rayint's .vtu reader agrees with vtkXMLUnstructuredGridReader bit for bit", "[vtk][vtkxml]") {
  const auto files = fixtures(".vtu");
  REQUIRE(files.size() >= 16);
  for (const fs::path& file : files) {
    INFO(file.filename().string());
    const auto grid = vtk_read<vtkXMLUnstructuredGridReader>(file);
    vtkPointData* pd = grid->GetPointData();
    int compared = 0;
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
      vtkDataArray* array = pd->GetArray(a);
      if (array == nullptr || array->GetNumberOfComponents() != 1) continue;
      INFO(array->GetName());
      const TetMesh m = read_vtu(file.string(), {array->GetName()});
      REQUIRE(static_cast<vtkIdType>(m.points.size()) == grid->GetNumberOfPoints());
      REQUIRE(static_cast<vtkIdType>(m.tets.size()) == grid->GetNumberOfCells());
      for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
        double p[3];
        grid->GetPoint(i, p);
        for (int k = 0; k < 3; ++k) CHECK(m.points[static_cast<std::size_t>(i)][k] == p[k]);
        CHECK(m.scalars[static_cast<std::size_t>(i)] == array->GetComponent(i, 0));
      }
      vtkNew<vtkIdList> ids;
      for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
        grid->GetCellPoints(c, ids);
        REQUIRE(ids->GetNumberOfIds() == 4);
        for (int k = 0; k < 4; ++k) CHECK(m.tets[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] == ids->GetId(k));
      }
      ++compared;
    }
    CHECK(compared >= 1);
  }
}

TEST_CASE("rayint's .vti reader agrees with vtkXMLImageDataReader bit for bit", "[vtk][vtkxml]") {
  const auto files = fixtures(".vti");
  REQUIRE(files.size() >= 14);
  for (const fs::path& file : files) {
    if (file.filename() == "image-direction.vti") continue;  // refused by rayint (rotated)
    INFO(file.filename().string());
    const auto img = vtk_read<vtkXMLImageDataReader>(file);
    int dims[3];
    img->GetDimensions(dims);
    double first[3];
    img->GetPoint(0, first);
    vtkPointData* pd = img->GetPointData();
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a) {
      vtkDataArray* array = pd->GetArray(a);
      INFO(array->GetName());
      const VoxelGrid g = read_vti(file.string(), array->GetName());
      for (int k = 0; k < 3; ++k) {
        CHECK(g.dims()[static_cast<std::size_t>(k)] == dims[k]);
        CHECK(g.spacing()[k] == img->GetSpacing()[k]);
        CHECK(g.origin()[k] == first[k]);
      }
      REQUIRE(static_cast<vtkIdType>(g.values().size()) == img->GetNumberOfPoints());
      for (vtkIdType i = 0; i < img->GetNumberOfPoints(); ++i)
        CHECK(g.values()[static_cast<std::size_t>(i)] == array->GetComponent(i, 0));
    }
  }
}
