// A VTK-style dataset into a TetMesh (see mesh_assembly.hpp for the rules).
#include "rayint/input/mesh_assembly.hpp"

#include <cmath>
#include <cstring>
#include <unordered_map>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"

namespace rayint {
namespace {

// vtkDataSetAttributes::DUPLICATECELL (vtkDataSetAttributes.h, CellGhostTypes).
constexpr unsigned kDuplicateCell = 1;

struct PointKey {
  std::uint64_t x, y, z;
  bool operator==(const PointKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    return std::hash<std::uint64_t>()(k.x * 0x9E3779B97F4A7C15ULL ^ (k.y + 0x632BE59BD9B4E019ULL) * 31 ^ k.z);
  }
};
std::uint64_t bits(double v) {
  if (v == 0.0) v = 0.0;  // -0 and +0 are the same point
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// The array taken as the scalar (the rule of mesh_assembly.hpp), or one line naming what exists.
RawArray& choose_scalar(RawMesh& raw, const std::string& source, const AssemblyOptions& options,
                        const RawMeshFields& fields, const MeshFileInfo& info) {
  const RawArray* chosen = find_scalar_array(raw.arrays, options);
  if (chosen == nullptr && !options.scalar.name.empty())
    field::fail(source, fields.point_data,
                "no array named " + field::quoted(options.scalar.name) + " (arrays: " + list_arrays(info.arrays) + ")");
  if (chosen == nullptr)
    field::fail(source, fields.point_data,
                "no field to integrate: no one-component point or cell array that is not a region marker (arrays: " +
                    list_arrays(info.arrays) + ")");
  if (chosen->components != 1)
    field::fail(source, fields.point_data,
                "array " + field::quoted(chosen->name) + " has " + std::to_string(chosen->components) +
                    " components; the scalar needs 1");
  // One of raw.arrays, which the assembly owns: its values may move into the mesh.
  return raw.arrays[static_cast<std::size_t>(chosen - raw.arrays.data())];
}


// What both assemblies share: the offsets check, the array list, the ghost flags and the points
// (merged across pieces when asked). `points` and `info` are the mesh's.
struct Shared {
  std::vector<char> ghost;                 // per cell: a duplicate cell of another piece
  std::vector<std::int32_t> point_map;     // file point index -> mesh point index
  std::size_t file_points = 0;             // the file's point count (raw.points may have been moved out)
};
Shared assemble_shared(RawMesh& raw, const std::string& source, const AssemblyOptions& options,
                       const RawMeshFields& fields, std::vector<Vec3>& points, MeshFileInfo& info) {
  const std::size_t n_cells = raw.types.size();
  if (raw.offsets.size() != n_cells + 1)
    field::fail(source, fields.cells, std::to_string(raw.offsets.size() - 1) + " cells for " +
                                          std::to_string(n_cells) + " cell types");
  for (const RawArray& a : raw.arrays)
    info.arrays.push_back({a.name, a.cell ? "cell" : "point", static_cast<long>(a.components), is_marker_array(a.name)});
  Shared out;
  out.file_points = raw.points.size();
  out.ghost.assign(n_cells, 0);
  for (const RawArray& a : raw.arrays)
    if (a.cell && a.name == "vtkGhostType" && a.components == 1 && a.values.size() == n_cells)
      for (std::size_t i = 0; i < n_cells; ++i)
        if (static_cast<unsigned>(a.values[i]) & kDuplicateCell) out.ghost[i] = 1;
  out.point_map.resize(raw.points.size());
  if (options.merge_points) {
    std::unordered_map<PointKey, std::int32_t, PointKeyHash> seen;
    seen.reserve(raw.points.size());
    for (std::size_t i = 0; i < raw.points.size(); ++i) {
      const Vec3& p = raw.points[i];
      const auto [it, fresh] = seen.emplace(PointKey{bits(p[0]), bits(p[1]), bits(p[2])},
                                            static_cast<std::int32_t>(points.size()));
      if (fresh) points.push_back(p);
      else ++info.merged_points;
      out.point_map[i] = it->second;
    }
  } else {
    points = std::move(raw.points);  // the raw points are not used again (file_points counts them)
    for (std::size_t i = 0; i < out.point_map.size(); ++i) out.point_map[i] = static_cast<std::int32_t>(i);
  }
  return out;
}

// Cell i through the table: counted by type; nullptr for a ghost or a skipped (dimension 0-2)
// cell, refused with one line when `accepted` says the assembly cannot take it; otherwise its row,
// after checking that its offsets fit the connectivity and give the type's node count.
// `last`: the previous cell's type, its row and its count in info.cells_by_type (std::map: the
// address is stable), so a run of cells of one type costs no table or map lookup per cell.
struct LastType {
  long long type = -1;
  const CellTypeInfo* row = nullptr;
  long* count = nullptr;
  bool accepted = false;  // accepted(row->support), asked once per run of a type
};
const CellTypeInfo* table_cell(const RawMesh& raw, std::size_t i, const Shared& shared, const std::string& source,
                               const RawMeshFields& fields, MeshFileInfo& info, bool (*accepted)(CellSupport),
                               LastType& last) {
  const long long type = raw.types[i];
  // The field's name is built only for a message (a string per cell was ~1% of the load).
  const auto at = [&] { return fields.types + "[" + std::to_string(i) + "]"; };
  if (last.row == nullptr || type != last.type) {
    const CellTypeInfo* found = cell_type_from_vtk(type);
    if (found == nullptr) field::fail(source, at(), unsupported_cell_message(type));
    last = LastType{type, found, &info.cells_by_type[found->name], accepted(found->support)};
  }
  const CellTypeInfo* row = last.row;
  ++*last.count;
  if (shared.ghost[i]) {
    ++info.ghost_cells;
    return nullptr;
  }
  if (row->support == CellSupport::Skipped) {
    ++info.skipped_cells;
    ++info.skipped_by_type[row->name];
    return nullptr;
  }
  if (!last.accepted) field::fail(source, at(), unsupported_cell_message(type));
  const std::size_t b = raw.offsets[i], e = raw.offsets[i + 1];
  if (e < b || e > raw.connectivity.size())
    field::fail(source, fields.cells + "[" + std::to_string(i) + "]", "offsets run outside the connectivity");
  if (e - b != static_cast<std::size_t>(row->nodes))
    field::fail(source, fields.cells + "[" + std::to_string(i) + "]",
                std::string("a ") + row->name + " needs " + std::to_string(row->nodes) + " points, got " +
                    std::to_string(e - b));
  return row;
}


// File point index connectivity[k] of cell i (its local node `local`) as a mesh point index; one
// line naming the field when it is out of range.
std::int32_t mesh_point(const RawMesh& raw, std::size_t k, std::size_t i, std::size_t local, const Shared& shared,
                        const std::string& source, const RawMeshFields& fields) {
  const long long p = raw.connectivity[k];
  const auto n_points = static_cast<long long>(shared.file_points);
  if (p < 0 || p >= n_points)
    field::fail(source, fields.cells + "[" + std::to_string(i) + "][" + std::to_string(local) + "]",
                "point index " + std::to_string(p) + " out of range [0, " + std::to_string(n_points) + ")");
  return shared.point_map[static_cast<std::size_t>(p)];
}

// The scalar of both assemblies: the chosen array (choose_scalar) as cell values of the kept
// cells, as point values (pieces' shared points must agree), or a cell array averaged to points
// as vtkCellDataToPointData does (every cell of the dataset that uses the point, boundary cells
// too, plain average). Returns the field name the values came from, for later messages.
std::string assign_scalar(RawMesh& raw, const std::string& source, const AssemblyOptions& options,
                          const RawMeshFields& fields, const Shared& shared, std::size_t mesh_points,
                          MeshFileInfo& info, std::vector<double>& scalars, std::vector<double>& cell_scalars) {
  const std::size_t n_cells = raw.types.size();
  RawArray& chosen = choose_scalar(raw, source, options, fields, info);
  const std::string where = chosen.cell ? fields.cell_data : fields.point_data;
  const std::size_t expected = chosen.cell ? n_cells : shared.file_points;
  if (chosen.values.size() != expected)
    field::fail(source, where, "array " + field::quoted(chosen.name) + " has " + std::to_string(chosen.values.size()) +
                                   " values for " + std::to_string(expected) + (chosen.cell ? " cells" : " points"));
  info.scalar = chosen.name;
  info.scalar_association = chosen.cell ? "cell" : "point";
  if (chosen.cell && !options.scalar.cell_to_point) {
    // The kept cells are info.cell_ids (file cell indices, ascending).
    cell_scalars.reserve(info.cell_ids.size());
    for (const long long c : info.cell_ids) cell_scalars.push_back(chosen.values[static_cast<std::size_t>(c)]);
  } else if (chosen.cell) {
    std::vector<double> sum(mesh_points, 0.0);
    std::vector<long> count(mesh_points, 0);
    const auto n_points = static_cast<long long>(shared.file_points);
    for (std::size_t c = 0; c < n_cells; ++c)
      for (std::size_t k = raw.offsets[c]; k < raw.offsets[c + 1] && k < raw.connectivity.size(); ++k) {
        const long long p = raw.connectivity[k];
        if (p < 0 || p >= n_points) continue;
        const auto j = static_cast<std::size_t>(shared.point_map[static_cast<std::size_t>(p)]);
        sum[j] += chosen.values[c];
        ++count[j];
      }
    for (std::size_t j = 0; j < sum.size(); ++j)
      if (count[j] > 0) sum[j] /= static_cast<double>(count[j]);
    scalars = std::move(sum);
    info.scalar_association = "cell averaged to points";
  } else if (options.merge_points) {
    scalars.assign(mesh_points, 0.0);
    std::vector<char> set(mesh_points, 0);
    for (std::size_t i = 0; i < shared.file_points; ++i) {
      const auto j = static_cast<std::size_t>(shared.point_map[i]);
      const double v = chosen.values[i];
      if (set[j] && !(scalars[j] == v))
        field::fail(source, where, "array " + field::quoted(chosen.name) + ": point " + std::to_string(i) +
                                       " repeats another piece's point with a different value (" +
                                       format_number(scalars[j]) + " and " + format_number(v) + ")");
      scalars[j] = v;
      set[j] = 1;
    }
  } else {
    scalars = std::move(chosen.values);  // not read again: raw is this assembly's own
  }
  return where;
}

// Both assemblies: the points (assemble_shared), then each cell through the table (table_cell
// with `accepted`); `take(row, node)` stores a kept cell, node(local) giving the mesh point of
// its local node (mesh_point). Kept cells are recorded in info.cell_ids; none kept is one line
// ("no WHAT (N cells, K of dimension 0-2 skipped, G ghost)"). Then the scalar (assign_scalar),
// whose field name is returned for later messages.
template <class Mesh, class Take>
std::string assemble_cells(RawMesh& raw, const std::string& source, const AssemblyOptions& options,
                           const RawMeshFields& fields, Mesh& mesh, const char* what,
                           bool (*accepted)(CellSupport), Take take) {
  const std::size_t n_cells = raw.types.size();
  MeshFileInfo& info = mesh.info;
  const Shared shared = assemble_shared(raw, source, options, fields, mesh.points, info);
  info.cell_ids.reserve(n_cells);
  prefault_capacity(info.cell_ids);
  LastType last;
  for (std::size_t i = 0; i < n_cells; ++i) {
    const CellTypeInfo* row = table_cell(raw, i, shared, source, fields, info, accepted, last);
    if (row == nullptr) continue;
    take(*row, [&](std::size_t local) {
      return mesh_point(raw, raw.offsets[i] + local, i, local, shared, source, fields);
    });
    info.cell_ids.push_back(static_cast<long long>(i));
  }
  if (info.cell_ids.empty())
    field::fail(source, fields.cells,
                std::string("no ") + what + " (" + std::to_string(n_cells) + " cells, " +
                    std::to_string(info.skipped_cells) + " of dimension 0-2 skipped, " +
                    std::to_string(info.ghost_cells) + " ghost)");
  return assign_scalar(raw, source, options, fields, shared, mesh.points.size(), info, mesh.scalars,
                       mesh.cell_scalars);
}

}  // namespace

const RawArray* find_scalar_array(const std::vector<RawArray>& arrays, const AssemblyOptions& options) {
  if (!options.scalar.name.empty()) {  // by name: point data first, then cell data
    for (int pass = 0; pass < 2; ++pass)
      for (const RawArray& a : arrays)
        if (a.cell == (pass == 1) && a.name == options.scalar.name) return &a;
    return nullptr;
  }
  for (const RawArray& a : arrays)
    if (!a.cell && a.active && a.components == 1 && !is_marker_array(a.name)) return &a;
  for (int pass = 0; pass < 2; ++pass)
    for (const RawArray& a : arrays)
      if (a.cell == (pass == 1) && a.components == 1 && !is_marker_array(a.name)) return &a;
  return nullptr;
}

std::string list_arrays(const std::vector<MeshArrayInfo>& arrays) {
  if (arrays.empty()) return "none";
  std::string out;
  for (const MeshArrayInfo& a : arrays)
    out += (out.empty() ? "" : ", ") + field::quoted(a.name) + " (" + a.association + ", " +
           std::to_string(a.components) + (a.components == 1 ? " component" : " components") +
           (a.marker ? ", a marker" : "") + ")";
  return out;
}

TetMesh assemble_tet_mesh(RawMesh raw, const std::string& source, const AssemblyOptions& options,
                          const RawMeshFields& fields) {
  // Quadratic tetrahedra: corners as a tet, the six mid-edge nodes (VTK's order) beside it.
  TetMesh mesh;
  mesh.tets.reserve(raw.types.size());
  prefault_capacity(mesh.tets);
  // edge_nodes only once a quadratic tet comes: the linear tets before it get -1 rows then, and
  // a mesh of linear tets never allocates them (24 B a tet that stayed allocated: issue 33).
  const std::array<std::int32_t, 6> linear{-1, -1, -1, -1, -1, -1};
  const std::string where = assemble_cells(
      raw, source, options, fields, mesh, "tetrahedra",
      [](CellSupport support) { return support == CellSupport::Traversed || support == CellSupport::Quadratic; },
      [&](const CellTypeInfo& row, const auto& node) {
        std::array<std::int32_t, 4> t{};
        for (std::size_t k = 0; k < 4; ++k) t[k] = node(k);
        mesh.tets.push_back(t);
        if (row.support == CellSupport::Quadratic) {
          if (mesh.edge_nodes.empty()) {
            mesh.edge_nodes.reserve(raw.types.size());
            mesh.edge_nodes.assign(mesh.tets.size() - 1, linear);
          }
          std::array<std::int32_t, 6>& e = mesh.edge_nodes.emplace_back();
          for (std::size_t k = 0; k < 6; ++k) e[k] = node(4 + k);
        } else if (!mesh.edge_nodes.empty()) {
          mesh.edge_nodes.push_back(linear);
        }
      });
  validate_tet_mesh_structure(mesh, source, MeshFieldNames{fields.points, where, fields.cells});
  return mesh;
}

CellMesh assemble_cell_mesh(RawMesh raw, const std::string& source, const AssemblyOptions& options,
                            const RawMeshFields& fields) {
  // Linear volume cells and quadratic ones kept with all their nodes.
  CellMesh mesh;
  const std::string where = assemble_cells(
      raw, source, options, fields, mesh, "volume cells",
      [](CellSupport support) {
        return support == CellSupport::Traversed || support == CellSupport::CellPath ||
               support == CellSupport::Quadratic || support == CellSupport::Isoparametric;
      },
      [&](const CellTypeInfo& row, const auto& node) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(row.nodes); ++k) mesh.connectivity.push_back(node(k));
        mesh.types.push_back(static_cast<MeshCellType>(row.vtk_id));
        mesh.offsets.push_back(static_cast<std::uint32_t>(mesh.connectivity.size()));
      });
  validate_cell_mesh_structure(mesh, source, MeshFieldNames{fields.points, where, fields.cells});
  return mesh;
}

}  // namespace rayint
