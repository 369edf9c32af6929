// Validation of tetrahedral meshes (see tet_mesh.hpp for the checks and the orientation rule).
#include "rayint/mesh/tet_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/geometry/bounds.hpp"

namespace rayint {
namespace {

[[noreturn]] void fail(const std::string& source, const std::string& field, const std::string& what) {
  throw InputError(source + ": " + field + ": " + what);
}

std::string at(const std::string& field, std::size_t i) { return field + "[" + std::to_string(i) + "]"; }


}  // namespace

double signed_volume6(const TetMesh& mesh, std::size_t tet) {
  const auto& t = mesh.tets[tet];
  const Vec3& p0 = mesh.points[t[0]];
  return (mesh.points[t[1]] - p0).cross(mesh.points[t[2]] - p0).dot(mesh.points[t[3]] - p0);
}

// Swapping corners 2 and 3 maps VTK's edges (0,1) (1,2) (0,2) (0,3) (1,3) (2,3) onto
// (0,1) (1,3) (0,3) (0,2) (1,2) (3,2): mid-edge nodes 1 <-> 4 and 2 <-> 3 follow their edges.
static void swap_corners_2_3(TetMesh& mesh, std::size_t tet) {
  std::swap(mesh.tets[tet][2], mesh.tets[tet][3]);
  if (mesh.edge_nodes.empty()) return;
  auto& e = mesh.edge_nodes[tet];
  std::swap(e[1], e[4]);
  std::swap(e[2], e[3]);
}

std::size_t reorient_tets(TetMesh& mesh) {
  std::size_t swapped = 0;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    if (signed_volume6(mesh, i) < 0.0) {
      swap_corners_2_3(mesh, i);
      ++swapped;
    }
  }
  return swapped;
}

TetShape classify_tet(const TetMesh& mesh, std::size_t tet) {
  const auto& t = mesh.tets[tet];
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      if (t[a] == t[b]) return TetShape::ZeroVolume;
  const double v6 = signed_volume6(mesh, tet);
  if (v6 == 0.0) return TetShape::ZeroVolume;
  double longest = 0.0;
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = a + 1; b < 4; ++b)
      longest = std::max(longest, (mesh.points[t[a]] - mesh.points[t[b]]).norm());
  if (!(std::fabs(v6) > kDegenerateTetRatio * longest * longest * longest)) return TetShape::Sliver;
  return v6 < 0.0 ? TetShape::Inverted : TetShape::Positive;
}

void check_mesh_extent(const std::vector<Vec3>& points, const std::string& source, const MeshFieldNames& names) {
  const Bounds box = point_bounds(points);
  const double extent = (box.upper - box.lower).norm();
  if (extent > 0.0 && extent < kMinMeshExtent)
    fail(source, names.points,
         "the points span " + format_number(extent) + " (box diagonal), below " + format_number(kMinMeshExtent) +
             ": tetrahedron volumes and face areas underflow in double precision there; scale the mesh (and the "
             "densities by the inverse)");
}

void validate_tet_mesh_structure(const TetMesh& mesh, const std::string& source,
                                 const MeshFieldNames& names) {
  if (mesh.points.empty()) fail(source, names.points, "no points");
  if (mesh.tets.empty()) fail(source, names.tets, "no tetrahedra");
  if (!mesh.cell_scalars.empty()) {
    if (mesh.cell_scalars.size() != mesh.tets.size())
      fail(source, names.scalars,
           std::to_string(mesh.cell_scalars.size()) + " cell scalars for " + std::to_string(mesh.tets.size()) +
               " tetrahedra (need one per cell)");
    for (std::size_t i = 0; i < mesh.cell_scalars.size(); ++i)
      if (!std::isfinite(mesh.cell_scalars[i]))
        fail(source, at(names.scalars, i), "must be finite, got " + format_number(mesh.cell_scalars[i]));
  } else if (mesh.scalars.size() != mesh.points.size())
    fail(source, names.scalars,
         std::to_string(mesh.scalars.size()) + " scalars for " + std::to_string(mesh.points.size()) +
             " points (need one per point)");
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(mesh.points[i][k]))
        fail(source, at(at(names.points, i), static_cast<std::size_t>(k)),
             "coordinate must be finite, got " + format_number(mesh.points[i][k]));
  check_mesh_extent(mesh.points, source, names);
  for (std::size_t i = 0; i < mesh.scalars.size(); ++i)
    if (!std::isfinite(mesh.scalars[i]))
      fail(source, at(names.scalars, i),
           "must be finite, got " + format_number(mesh.scalars[i]));
  const auto n = static_cast<long long>(mesh.points.size());
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const auto& t = mesh.tets[i];
    for (std::size_t k = 0; k < 4; ++k)
      if (t[k] < 0 || t[k] >= n)
        fail(source, at(at(names.tets, i), k),
             "point index " + std::to_string(t[k]) + " out of range [0, " + std::to_string(n) + ")");
  }
  if (!mesh.edge_nodes.empty()) {
    if (mesh.edge_nodes.size() != mesh.tets.size())
      fail(source, names.tets, std::to_string(mesh.edge_nodes.size()) + " mid-edge node lists for " +
                                   std::to_string(mesh.tets.size()) + " tetrahedra");
    for (std::size_t i = 0; i < mesh.edge_nodes.size(); ++i)
      for (std::size_t k = 0; k < 6; ++k) {
        const std::int32_t p = mesh.edge_nodes[i][k];
        if (p < -1 || p >= n)
          fail(source, at(at(names.tets, i), 4 + k),
               "point index " + std::to_string(p) + " out of range [0, " + std::to_string(n) + ")");
      }
  }
}

void validate_tet_mesh(const TetMesh& mesh, const std::string& source, const MeshFieldNames& names) {
  validate_tet_mesh_structure(mesh, source, names);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const auto& t = mesh.tets[i];
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = a + 1; b < 4; ++b)
        if (t[a] == t[b])
          fail(source, at(names.tets, i),
               "degenerate tetrahedron: point " + std::to_string(t[a]) + " appears twice");
    const TetShape shape = classify_tet(mesh, i);
    const double v6 = signed_volume6(mesh, i);
    if (shape == TetShape::ZeroVolume || shape == TetShape::Sliver)
      fail(source, at(names.tets, i),
           "degenerate tetrahedron (volume " + format_number(v6 / 6.0) +
               ", flat or with coincident points)");
    if (shape == TetShape::Inverted)
      fail(source, at(names.tets, i),
           "inverted tetrahedron (negative volume " + format_number(v6 / 6.0) +
               "); order points so that (p1-p0)x(p2-p0).(p3-p0) > 0, as VTK does");
  }
}

TetRepairs repair_tet_mesh(TetMesh& mesh, const std::string& source, const MeshFieldNames& names) {
  TetRepairs r;
  r.tets_read = static_cast<long>(mesh.tets.size());
  r.skipped_cells = mesh.info.skipped_cells;
  r.skipped_by_type = mesh.info.skipped_by_type;
  r.ghost_cells = mesh.info.ghost_cells;
  const bool per_cell = !mesh.cell_scalars.empty();
  const bool ids = mesh.info.cell_ids.size() == mesh.tets.size();
  const bool quadratic = !mesh.edge_nodes.empty();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    switch (classify_tet(mesh, i)) {
      case TetShape::ZeroVolume: ++r.zero_volume; continue;
      case TetShape::Sliver: ++r.slivers; continue;
      case TetShape::Inverted:
        swap_corners_2_3(mesh, i);
        ++r.reoriented;
        break;
      case TetShape::Positive: break;
    }
    if (per_cell) mesh.cell_scalars[kept] = mesh.cell_scalars[i];
    if (ids) mesh.info.cell_ids[kept] = mesh.info.cell_ids[i];
    if (quadratic) mesh.edge_nodes[kept] = mesh.edge_nodes[i];
    mesh.tets[kept++] = mesh.tets[i];
  }
  mesh.tets.resize(kept);
  if (quadratic) mesh.edge_nodes.resize(kept);
  if (per_cell) mesh.cell_scalars.resize(kept);
  if (ids) mesh.info.cell_ids.resize(kept);
  if (mesh.tets.empty())
    fail(source, names.tets,
         "every tetrahedron is degenerate (" + std::to_string(r.zero_volume) + " zero-volume, " +
             std::to_string(r.slivers) + " slivers): nothing to traverse");
  return r;
}

// Besides the names in tet_mesh.hpp: "CellEntityIds", the elementary entity of each cell that
// gmsh's own legacy VTK writer (-format vtk) adds as cell data.
bool is_marker_array(const std::string& name) {
  static const char* const exact[] = {"gmsh:physical", "gmsh:geometrical", "gmsh:dim_tags", "CellEntityIds", "medit:ref",
                                      "tetgen:ref", "flac3d:zone", "avsucd:material", "cell_tags",
                                      "point_tags", "vtkGhostType", "vtkOriginalPointIds",
                                      "vtkOriginalCellIds", "vtkProcessId", "region", "marker",
                                      "material_id", "subdomain"};
  for (const char* e : exact)
    if (name == e) return true;
  return false;
}

std::vector<double> cell_to_point_average(const TetMesh& mesh) {
  std::vector<double> sum(mesh.points.size(), 0.0);
  std::vector<long> count(mesh.points.size(), 0);
  for (std::size_t c = 0; c < mesh.tets.size(); ++c) {
    for (const std::int32_t p : mesh.tets[c]) {
      sum[static_cast<std::size_t>(p)] += mesh.cell_scalars[c];
      ++count[static_cast<std::size_t>(p)];
    }
    if (c < mesh.edge_nodes.size())  // a quadratic tet's mid-edge nodes are its points too
      for (const std::int32_t p : mesh.edge_nodes[c])
        if (p >= 0) {
          sum[static_cast<std::size_t>(p)] += mesh.cell_scalars[c];
          ++count[static_cast<std::size_t>(p)];
        }
  }
  for (std::size_t i = 0; i < sum.size(); ++i)
    if (count[i] > 0) sum[i] /= static_cast<double>(count[i]);
  return sum;
}

}  // namespace rayint
