#pragma once
// What every mesh-reader fuzz target checks (vtk_legacy, tetgen, gmsh; structured_grid and
// vti_reader: check_structured_cells): an accepted mesh keeps
// the readers' guarantees (tet_mesh.hpp, validate_tet_mesh_structure) and then goes through what a
// mesh case does with it — repair_tet_mesh, the curved-tet10 refusal and, when small, the
// traversal of one ray (quadratic crossings for tet10) — and every
// refusal is one InputError line starting "<source>: ". Each check traps, so libFuzzer saves the
// input as a crash artifact.
#include <cmath>
#include <string>

#include "rayint/core/error.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "fuzz_checks.hpp"

namespace rayint::fuzz {

// The accepted mesh: structure as promised, then the mesh-case path.
inline void check_mesh(TetMesh mesh, const std::string& source) {
  // Point data (one scalar per point) or cell data (one per tet, TetMesh::cell_scalars).
  require(!mesh.points.empty() && !mesh.tets.empty() &&
          (mesh.cell_scalars.empty() ? mesh.scalars.size() == mesh.points.size()
                                     : mesh.cell_scalars.size() == mesh.tets.size()));
  for (const Vec3& p : mesh.points) require(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()));
  for (const double s : mesh.scalars) require(std::isfinite(s));
  for (const double s : mesh.cell_scalars) require(std::isfinite(s));
  for (const auto& t : mesh.tets)
    for (const auto i : t) require(i >= 0 && static_cast<std::size_t>(i) < mesh.points.size());
  // Quadratic tets: one list of six mid-edge nodes per tet (-1: a linear tet's edge).
  require(mesh.edge_nodes.empty() || mesh.edge_nodes.size() == mesh.tets.size());
  for (const auto& e : mesh.edge_nodes)
    for (const auto i : e) require(i >= -1 && (i < 0 || static_cast<std::size_t>(i) < mesh.points.size()));
  try {
    const TetRepairs r = repair_tet_mesh(mesh, source);
    require(r.tets_read == r.zero_volume + r.slivers + static_cast<long>(mesh.tets.size()));
    validate_tet_mesh(mesh, source);  // after repair the strict check must pass
    require(mesh.edge_nodes.empty() || mesh.edge_nodes.size() == mesh.tets.size());  // repair kept them in step
    refuse_curved_tet10(mesh, source);  // what a mesh case does: straight-edged tet10 only
    if (mesh.tets.size() > 2000) return;
    const TetTraversal traversal(mesh, source);
    RayTrace trace;
    TraversalStats stats;
    const Vec3 centre = 0.5 * (traversal.box_min() + traversal.box_max());
    traversal.trace(ViewRay{centre + Vec3(0.31, 0.47, 10.0), Vec3(-0.031, -0.047, -1.0)}, trace, &stats);
    double last = -INFINITY;
    for (const CellCrossing& c : trace.crossings) {
      require(c.t_out > c.t_in && c.t_in >= last && std::isfinite(c.s_in) == std::isfinite(c.s_out));
      require(traversal.quadratic() || c.q == 0.0);
      last = c.t_out;
    }
  } catch (const InputError& e) {
    check_message(e.what(), source);  // every tet degenerate; a face in 3 tets; overlapping tets
  }
}

// A CellMesh (the readers' *_cells entry points): its structure as promised, then `--cells
// split` (mesh/cell_split.hpp) and the tetrahedral checks above on the result.
inline void check_cells(const CellMesh& mesh, const std::string& source) {
  require(mesh.cell_count() > 0 && mesh.offsets.size() == mesh.cell_count() + 1 &&
          mesh.offsets.back() == mesh.connectivity.size());
  require(mesh.cell_scalars.empty() ? mesh.scalars.size() == mesh.points.size()
                                    : mesh.cell_scalars.size() == mesh.cell_count());
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    require(mesh.nodes_of(c) == static_cast<std::size_t>(mesh_cell_nodes(static_cast<int>(mesh.types[c]))));
    for (std::size_t k = 0; k < mesh.nodes_of(c); ++k)
      require(mesh.cell(c)[k] >= 0 && static_cast<std::size_t>(mesh.cell(c)[k]) < mesh.points.size());
  }
  // Quadratic cells never reach the split: the case reader refuses them first, naming the file
  // (input/mesh_case_reader.cpp); split_cells' own refusal of them carries no file name.
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    if (is_quadratic(mesh.types[c])) return;
  try {
    check_mesh(split_cells(mesh), source);
  } catch (const InputError& e) {
    check_message(e.what(), source);  // e.g. every split tetrahedron degenerate
  }
}

// A structured grid's cells (.vts, .vtr, the cells of a .vti): at least one cell, node counts per
// cell type, indices in range, finite points and scalars, one scalar per point or cell, and
// structured dimensions that match the points.
inline void check_structured_cells(const CellMesh& m) {
  require(m.cell_count() > 0 && m.offsets.size() == m.cell_count() + 1);
  require(m.cell_scalars.empty() ? m.scalars.size() == m.points.size() : m.cell_scalars.size() == m.cell_count());
  for (const auto& p : m.points) require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
  for (double s : m.scalars) require(std::isfinite(s));
  for (double s : m.cell_scalars) require(std::isfinite(s));
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    require(m.nodes_of(c) == static_cast<std::size_t>(mesh_cell_nodes(static_cast<int>(m.types[c]))));
    for (std::size_t k = 0; k < m.nodes_of(c); ++k)
      require(m.cell(c)[k] >= 0 && static_cast<std::size_t>(m.cell(c)[k]) < m.points.size());
  }
  require(m.structured.has_value());
  const auto& d = *m.structured;
  require(static_cast<std::size_t>(d[0]) * static_cast<std::size_t>(d[1]) * static_cast<std::size_t>(d[2]) == m.points.size());
}

}  // namespace rayint::fuzz
