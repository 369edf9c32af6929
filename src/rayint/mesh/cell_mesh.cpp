// Meshes of linear cells (see cell_mesh.hpp).
#include "rayint/mesh/cell_mesh.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "rayint/cells/cell_types.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"

namespace rayint {
namespace {

std::string at(const std::string& path, std::size_t i) { return field::index_path(path, i); }

double det3(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

// Corner frames in VTK's parametric coordinates (r, s, t): per corner its node and the nodes one
// step along r, s, t, with the sign of that step (+1 towards larger parameter). The Jacobian
// det(dx/dr, dx/ds, dx/dt) at the corner has the sign of sr ss st det(x_r - x, x_s - x, x_t - x).
struct Corner {
  int node, r, s, t, sign;
};
// vtkHexahedron: 0 (0,0,0) 1 (1,0,0) 2 (1,1,0) 3 (0,1,0), 4-7 the same at t = 1.
constexpr Corner kHexCorners[8] = {{0, 1, 3, 4, +1}, {1, 0, 2, 5, -1}, {2, 3, 1, 6, +1}, {3, 2, 0, 7, -1},
                                   {4, 5, 7, 0, -1}, {5, 4, 6, 1, +1}, {6, 7, 5, 2, -1}, {7, 6, 4, 3, +1}};
// vtkVoxel: 0 (0,0,0) 1 (1,0,0) 2 (0,1,0) 3 (1,1,0), 4-7 the same at t = 1.
constexpr Corner kVoxelCorners[8] = {{0, 1, 2, 4, +1}, {1, 0, 3, 5, -1}, {3, 2, 1, 7, +1}, {2, 3, 0, 6, -1},
                                     {4, 5, 6, 0, -1}, {5, 4, 7, 1, +1}, {7, 6, 5, 3, -1}, {6, 7, 4, 2, +1}};
// vtkWedge: 0 (0,0,0) 1 (1,0,0) 2 (0,1,0), 3-5 the same at t = 1. At a triangle corner the frame
// (next - x, previous - x) has the orientation of (x1 - x0, x2 - x0) for every corner.
constexpr Corner kWedgeCorners[6] = {{0, 1, 2, 3, +1}, {1, 2, 0, 4, +1}, {2, 0, 1, 5, +1},
                                     {3, 4, 5, 0, -1}, {4, 5, 3, 1, -1}, {5, 3, 4, 2, -1}};
// vtkPyramid: base 0 (0,0,0) 1 (1,0,0) 2 (1,1,0) 3 (0,1,0), apex 4 (t = 1; the apex is singular).
constexpr Corner kPyramidCorners[4] = {{0, 1, 3, 4, +1}, {1, 0, 2, 4, -1}, {2, 3, 1, 4, +1}, {3, 2, 0, 4, -1}};
constexpr Corner kTetCorners[1] = {{0, 1, 2, 3, +1}};

template <std::size_t N>
int corner_signs(const CellMesh& m, const std::int32_t* c, const Corner (&corners)[N]) {
  int pos = 0, neg = 0;
  for (const Corner& k : corners) {
    const Vec3& x = m.points[static_cast<std::size_t>(c[k.node])];
    const double d = k.sign * det3(m.points[static_cast<std::size_t>(c[k.r])] - x,
                                   m.points[static_cast<std::size_t>(c[k.s])] - x,
                                   m.points[static_cast<std::size_t>(c[k.t])] - x);
    if (d > 0) ++pos;
    else if (d < 0) ++neg;
  }
  if (pos == static_cast<int>(N)) return 1;
  if (neg == static_cast<int>(N)) return -1;
  return 0;
}

}  // namespace

int mesh_cell_nodes(long long vtk_id) {
  // The table's count (cells/cell_types.hpp) for the types a CellMesh holds: those
  // assemble_cell_mesh keeps (input/mesh_assembly.hpp), the values of MeshCellType.
  const CellTypeInfo* row = cell_type_from_vtk(vtk_id);
  if (row == nullptr) return 0;
  switch (row->support) {
    case CellSupport::Traversed:
    case CellSupport::CellPath:
    case CellSupport::Quadratic:
    case CellSupport::Isoparametric: return row->nodes;
    case CellSupport::Skipped:
    case CellSupport::NotYet: return 0;
  }
  return 0;
}

bool is_quadratic(MeshCellType type) { return static_cast<int>(type) >= 24; }

const char* mesh_cell_name(MeshCellType type) {
  switch (type) {
    case MeshCellType::tetra: return "tetra";
    case MeshCellType::voxel: return "voxel";
    case MeshCellType::hexahedron: return "hexahedron";
    case MeshCellType::wedge: return "wedge";
    case MeshCellType::pyramid: return "pyramid";
    case MeshCellType::quadratic_tetra: return "quadratic tetra";
    case MeshCellType::quadratic_hexahedron: return "quadratic hexahedron";
    case MeshCellType::quadratic_wedge: return "quadratic wedge";
    case MeshCellType::quadratic_pyramid: return "quadratic pyramid";
    case MeshCellType::triquadratic_hexahedron: return "triquadratic hexahedron";
    case MeshCellType::biquadratic_quadratic_wedge: return "biquadratic-quadratic wedge";
  }
  return "?";
}

bool CellMesh::only_tets() const {
  for (MeshCellType t : types)
    if (t != MeshCellType::tetra) return false;
  return true;
}

std::vector<std::pair<std::string, long>> cell_counts(const CellMesh& mesh) {
  std::map<int, long> n;
  for (MeshCellType t : mesh.types) ++n[static_cast<int>(t)];
  std::vector<std::pair<std::string, long>> out;
  for (const auto& [id, count] : n) out.emplace_back(mesh_cell_name(static_cast<MeshCellType>(id)), count);
  return out;
}

void validate_cell_mesh_structure(const CellMesh& mesh, const std::string& source, const MeshFieldNames& names) {
  if (mesh.points.empty()) field::fail(source, names.points, "no points");
  if (mesh.types.empty()) field::fail(source, names.tets, "no volume cells");
  if (mesh.offsets.size() != mesh.types.size() + 1 || mesh.offsets.back() != mesh.connectivity.size())
    field::fail(source, names.tets, "cell offsets do not match the connectivity");
  if (!mesh.cell_scalars.empty()) {
    if (mesh.cell_scalars.size() != mesh.types.size())
      field::fail(source, names.scalars,
                  std::to_string(mesh.cell_scalars.size()) + " cell scalars for " + std::to_string(mesh.types.size()) +
                      " cells (need one per cell)");
    for (std::size_t i = 0; i < mesh.cell_scalars.size(); ++i)
      if (!std::isfinite(mesh.cell_scalars[i]))
        field::fail(source, at(names.scalars, i), "must be finite, got " + format_number(mesh.cell_scalars[i]));
  } else if (mesh.scalars.size() != mesh.points.size()) {
    field::fail(source, names.scalars,
                std::to_string(mesh.scalars.size()) + " scalars for " + std::to_string(mesh.points.size()) +
                    " points (need one per point)");
  }
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(mesh.points[i][k]))
        field::fail(source, at(at(names.points, i), static_cast<std::size_t>(k)),
                    "coordinate must be finite, got " + format_number(mesh.points[i][k]));
  check_mesh_extent(mesh.points, source, names);
  for (std::size_t i = 0; i < mesh.scalars.size(); ++i)
    if (!std::isfinite(mesh.scalars[i]))
      field::fail(source, at(names.scalars, i), "must be finite, got " + format_number(mesh.scalars[i]));
  const auto n = static_cast<long long>(mesh.points.size());
  for (std::size_t c = 0; c < mesh.types.size(); ++c) {
    const int want = mesh_cell_nodes(static_cast<int>(mesh.types[c]));
    if (want == 0 || static_cast<std::size_t>(want) != mesh.nodes_of(c))
      field::fail(source, at(names.tets, c),
                  std::string("a ") + mesh_cell_name(mesh.types[c]) + " needs " + std::to_string(want) +
                      " points, got " + std::to_string(mesh.nodes_of(c)));
    const std::int32_t* p = mesh.cell(c);
    for (std::size_t k = 0; k < mesh.nodes_of(c); ++k)
      if (p[k] < 0 || p[k] >= n)
        field::fail(source, at(at(names.tets, c), k),
                    "point index " + std::to_string(p[k]) + " out of range [0, " + std::to_string(n) + ")");
  }
}

namespace {
// What a TetMesh and a CellMesh hold alike (points, point or cell scalars, file info), moved from
// one to the other; the cells are the caller's.
template <class To, class From>
To with_fields_of(From& from) {
  To to;
  to.points = std::move(from.points);
  to.scalars = std::move(from.scalars);
  to.cell_scalars = std::move(from.cell_scalars);
  to.info = std::move(from.info);
  return to;
}
}  // namespace

CellMesh cell_mesh_of(TetMesh&& mesh) {
  CellMesh m = with_fields_of<CellMesh>(mesh);
  for (std::size_t c = 0; c < mesh.tets.size(); ++c) {
    m.connectivity.insert(m.connectivity.end(), mesh.tets[c].begin(), mesh.tets[c].end());
    const bool quadratic = c < mesh.edge_nodes.size() && mesh.edge_nodes[c][0] >= 0;
    if (quadratic) m.connectivity.insert(m.connectivity.end(), mesh.edge_nodes[c].begin(), mesh.edge_nodes[c].end());
    m.types.push_back(quadratic ? MeshCellType::quadratic_tetra : MeshCellType::tetra);
    m.offsets.push_back(static_cast<std::uint32_t>(m.connectivity.size()));
  }
  return m;
}

TetMesh take_tets(CellMesh&& mesh) {
  TetMesh t = with_fields_of<TetMesh>(mesh);
  t.tets.reserve(mesh.types.size());
  for (std::size_t c = 0; c < mesh.types.size(); ++c) {
    const std::int32_t* p = mesh.cell(c);
    t.tets.push_back({p[0], p[1], p[2], p[3]});
  }
  return t;
}

int cell_orientation(const CellMesh& mesh, std::size_t c) {
  const std::int32_t* p = mesh.cell(c);
  switch (mesh.types[c]) {
    case MeshCellType::tetra: return corner_signs(mesh, p, kTetCorners);
    case MeshCellType::voxel: return corner_signs(mesh, p, kVoxelCorners);
    case MeshCellType::hexahedron: return corner_signs(mesh, p, kHexCorners);
    case MeshCellType::wedge: return corner_signs(mesh, p, kWedgeCorners);
    case MeshCellType::pyramid: return corner_signs(mesh, p, kPyramidCorners);
    // Quadratic cells list their corners first: the corner Jacobians of the linear cell.
    case MeshCellType::quadratic_tetra: return corner_signs(mesh, p, kTetCorners);
    case MeshCellType::quadratic_hexahedron:
    case MeshCellType::triquadratic_hexahedron: return corner_signs(mesh, p, kHexCorners);
    case MeshCellType::quadratic_wedge:
    case MeshCellType::biquadratic_quadratic_wedge: return corner_signs(mesh, p, kWedgeCorners);
    case MeshCellType::quadratic_pyramid: return corner_signs(mesh, p, kPyramidCorners);
  }
  return 0;
}

bool zero_volume_cell(const CellMesh& mesh, std::size_t c) {
  // A quadratic cell's map is checked by its own validity test (cells/quadratic_isoparametric:
  // det J sampled, a folded or flat cell refused naming it); this test knows linear cells only.
  if (is_quadratic(mesh.types[c])) return false;
  const auto type = static_cast<LinearCellType>(static_cast<int>(mesh.types[c]));
  const int n = linear_node_count(type);
  const std::int32_t* ids = mesh.cell(c);
  double longest = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      longest = std::max(longest, (mesh.points[static_cast<std::size_t>(ids[i])] - mesh.points[static_cast<std::size_t>(ids[j])]).norm());
  const double limit = kDegenerateTetRatio * longest * longest * longest;
  double dN[3 * kMaxLinearNodes];
  for (int k = 0; k < 27; ++k) {
    const Vec3 p(0.5 * (k % 3), 0.5 * ((k / 3) % 3), 0.5 * (k / 9));
    linear_shape_derivatives(type, p, dN);
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < n; ++i) J.col(a) += dN[a * n + i] * mesh.points[static_cast<std::size_t>(ids[i])];
    if (!(std::fabs(J.determinant()) <= limit)) return false;  // NaN (never: points are finite) counts as volume
  }
  return true;
}

std::map<std::string, long> drop_zero_volume_cells(CellMesh& mesh, const std::string& source) {
  std::map<std::string, long> dropped;
  std::vector<char> drop(mesh.cell_count(), 0);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    if (zero_volume_cell(mesh, c)) {
      drop[c] = 1;
      ++dropped[mesh_cell_name(mesh.types[c])];
    }
  if (dropped.empty()) return dropped;
  if (static_cast<std::size_t>(std::count(drop.begin(), drop.end(), 1)) == mesh.cell_count())
    throw InputError(source + ": cells: every cell has zero volume (|det J| <= 1e-12 l^3 throughout): nothing to integrate");
  CellMesh kept;
  kept.points = std::move(mesh.points);
  kept.scalars = std::move(mesh.scalars);
  kept.info = std::move(mesh.info);
  kept.info.cell_ids.clear();
  for (std::size_t c = 0; c < drop.size(); ++c) {
    if (drop[c]) continue;
    kept.types.push_back(mesh.types[c]);
    kept.connectivity.insert(kept.connectivity.end(), mesh.cell(c), mesh.cell(c) + mesh.nodes_of(c));
    kept.offsets.push_back(static_cast<std::uint32_t>(kept.connectivity.size()));
    if (!mesh.cell_scalars.empty()) kept.cell_scalars.push_back(mesh.cell_scalars[c]);
    if (c < mesh.info.cell_ids.size()) kept.info.cell_ids.push_back(mesh.info.cell_ids[c]);
    else kept.info.cell_ids.push_back(static_cast<long long>(c));
  }
  // A structured grid with cells missing is no longer the full (i, j, k) block: its cells are
  // then split as unstructured cells (mesh/cell_split.hpp) where a split is asked for.
  kept.structured.reset();
  mesh = std::move(kept);
  return dropped;
}

void refuse_zero_volume_cells(const CellMesh& mesh, const std::string& source) {
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    if (zero_volume_cell(mesh, c))
      throw InputError(source + ": " + at("cells", c < mesh.info.cell_ids.size() ? static_cast<std::size_t>(mesh.info.cell_ids[c]) : c) +
                       ": a " + mesh_cell_name(mesh.types[c]) +
                       " of zero volume (|det J| <= 1e-12 l^3 throughout; the default drops and counts it, --strict-mesh refuses it)");
}

}  // namespace rayint
