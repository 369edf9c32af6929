// vtkDataSetTriangleFilter's tetrahedralisation (see cell_split.hpp).
#include "rayint/mesh/cell_split.hpp"

#include <array>
#include <cstdint>

#include "rayint/cells/cell_types.hpp"
#include "rayint/cells/vtk_split.hpp"
#include "rayint/core/error.hpp"

namespace rayint {
namespace {

using Tet = std::array<int, 4>;  // local node indices

// The cells area's type of the same VTK id (both enums are VTK's ids 10-14).
LinearCellType linear_type(MeshCellType type) { return static_cast<LinearCellType>(static_cast<int>(type)); }

}  // namespace

TetMesh split_cells(const CellMesh& mesh, CellSplitCounts* counts) {
  TetMesh out;
  out.points = mesh.points;
  out.scalars = mesh.scalars;
  out.info = mesh.info;
  out.info.cell_ids.clear();
  CellSplitCounts local;
  CellSplitCounts& n = counts != nullptr ? *counts : local;
  n.structured = mesh.structured.has_value();
  const bool cell_data = !mesh.cell_scalars.empty();
  auto file_id = [&](std::size_t c) {
    return c < mesh.info.cell_ids.size() ? mesh.info.cell_ids[c] : static_cast<long long>(c);
  };
  auto emit = [&](std::size_t c, const std::int32_t* p, const Tet& t) {
    out.tets.push_back({p[t[0]], p[t[1]], p[t[2]], p[t[3]]});
    out.info.cell_ids.push_back(file_id(c));
    if (cell_data) out.cell_scalars.push_back(mesh.cell_scalars[c]);
    ++n.tets[mesh_cell_name(mesh.types[c])];
  };
  std::array<std::int64_t, 8> ids{};
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const MeshCellType type = mesh.types[c];
    if (is_quadratic(type))  // VTK splits them by ids and positions (cells/cell_types.hpp)
      throw InputError("cells[" + std::to_string(file_id(c)) + "]: " + quadratic_split_message(static_cast<int>(type)));
    const std::int32_t* p = mesh.cell(c);
    ++n.cells[mesh_cell_name(type)];
    if (type == MeshCellType::tetra) {
      emit(c, p, {0, 1, 2, 3});
      continue;
    }
    if (mesh.structured) {
      const auto& d = *mesh.structured;
      const std::size_t cx = static_cast<std::size_t>(d[0] - 1), cy = static_cast<std::size_t>(d[1] - 1);
      const std::size_t i = c % cx, j = (c / cx) % cy, k = c / (cx * cy);
      for (const Tet& t : vtk_structured_split(linear_type(type), (i + j + k) % 2 == 0 ? 0 : 1)) emit(c, p, t);
      continue;
    }
    const std::size_t nodes = mesh.nodes_of(c);
    for (std::size_t i = 0; i < nodes; ++i) ids[i] = p[i];
    for (const Tet& t : vtk_split(linear_type(type), ids.data())) emit(c, p, t);
  }
  return out;
}

}  // namespace rayint
