// vtk_mesh_reader.cpp -- .vtu / .pvtu tetrahedral meshes through VTK's XML readers into a TetMesh
// (points, one scalar per point, VTK_TETRA cells in VTK's node order), then rayint's own
// validate_tet_mesh. VTK's warning output is switched off so that bad input gives exactly the one
// InputError line rayint prints.
#include "rayint/vtk/vtk_mesh_reader.hpp"

#include <mutex>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"

namespace rayint {
namespace {

template <class Reader>
vtkSmartPointer<vtkUnstructuredGrid> read_grid(const std::string& path, const char* reader_name) {
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<Reader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(path + ": file: not readable by " + reader_name);
  json_source::InputFileLog::note(path);  // the shard fingerprint hashes the files a run read
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || grid == nullptr || grid->GetNumberOfPoints() == 0)
    throw InputError(path + ": file: " + reader_name + " read no points (damaged or empty file)");
  return grid;
}

}  // namespace

TetMesh read_vtk_unstructured_grid(const std::string& path, const std::string& scalar_name) {
  const bool parallel = path.size() >= 5 && path.compare(path.size() - 5, 5, ".pvtu") == 0;
  const vtkSmartPointer<vtkUnstructuredGrid> grid =
      parallel ? read_grid<vtkXMLPUnstructuredGridReader>(path, "vtkXMLPUnstructuredGridReader")
               : read_grid<vtkXMLUnstructuredGridReader>(path, "vtkXMLUnstructuredGridReader");
  // VTK opened the pieces itself: each is an input of the run too (the shard fingerprint hashes
  // every file read).
  if (parallel)
    for (const std::string& piece : pvtu_piece_files(path)) json_source::InputFileLog::note(piece);
  vtkPointData* pd = grid->GetPointData();
  vtkDataArray* scalars = nullptr;
  if (!scalar_name.empty()) {
    scalars = pd->GetArray(scalar_name.c_str());
    if (scalars == nullptr) throw InputError(path + ": PointData: no array named \"" + scalar_name + "\"");
  } else {
    scalars = pd->GetScalars();
    for (int i = 0; scalars == nullptr && i < pd->GetNumberOfArrays(); ++i)
      if (pd->GetArray(i) != nullptr && pd->GetArray(i)->GetNumberOfComponents() == 1) scalars = pd->GetArray(i);
    if (scalars == nullptr) throw InputError(path + ": PointData: no one-component point array for the scalar");
  }
  if (scalars->GetNumberOfComponents() != 1)
    throw InputError(path + ": PointData: array \"" + std::string(scalars->GetName() ? scalars->GetName() : "") +
                     "\" has " + std::to_string(scalars->GetNumberOfComponents()) + " components, need 1");

  TetMesh mesh;
  const vtkIdType n_points = grid->GetNumberOfPoints();
  mesh.points.reserve(static_cast<std::size_t>(n_points));
  mesh.scalars.reserve(static_cast<std::size_t>(n_points));
  for (vtkIdType i = 0; i < n_points; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    mesh.points.emplace_back(p[0], p[1], p[2]);
    mesh.scalars.push_back(scalars->GetComponent(i, 0));
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    const int type = grid->GetCellType(c);
    if (type != VTK_TETRA)
      throw InputError(path + ": Cells[" + std::to_string(c) + "]: cell type " + std::to_string(type) +
                       " (only tetrahedra, type 10, are read)");
    grid->GetCellPoints(c, ids);
    std::array<std::int32_t, 4> tet{};
    for (int k = 0; k < 4; ++k) tet[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(ids->GetId(k));
    mesh.tets.push_back(tet);
  }
  validate_tet_mesh(mesh, path, MeshFieldNames{"Points", "PointData", "Cells"});
  return mesh;
}

void register_vtk_mesh_readers() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_mesh_reader(".vtu", read_vtk_unstructured_grid);
    register_mesh_reader(".pvtu", read_vtk_unstructured_grid);
  });
}

}  // namespace rayint
