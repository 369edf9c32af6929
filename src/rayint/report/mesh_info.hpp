#pragma once
// `rayint mesh info FILE [--check]`: what a mesh file holds as rayint reads it, as JSON or as a
// few lines of text: bounds, cells by type (kept / skipped / ghost), the arrays with their
// association and components, which one is the scalar, orientation counts and, with --check, the
// overlap check (mesh/mesh_check.hpp). A file with hexahedra, wedges, pyramids or voxels is
// reported by cell type, with each type's orientation counts (cell_mesh.hpp) and the line
// "integrated: with --cells split (VTK's tetrahedralisation, an approximation)". Quadratic
// tetrahedra: their count and "edges straight" (integrated with their quadratic interpolation) or
// "edges curved" (integrated isoparametrically on the own-cells path), with the largest mid-edge offset and its cell.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

struct MeshInfo {
  std::string file;
  const TetMesh* mesh = nullptr;
  // A file with cells other than tetrahedra (mesh/cell_mesh.hpp): reported instead of `mesh`,
  // with per type the corner-Jacobian orientation (cell_orientation) and how it is integrated.
  const CellMesh* cells = nullptr;
  OrientationCounts orientation;
  bool checked = false;                                        // --check ran
  std::optional<std::pair<std::size_t, std::size_t>> overlap;  // its finding
  double check_seconds = 0.0;
  // Quadratic tetrahedra (mesh/quadratic_tets.hpp): how many, and whether their edges are
  // straight (integrated exactly) or curved (integrated isoparametrically), with the worst mid-edge node's offset.
  std::optional<Tet10EdgeCheck> tet10;
};

nlohmann::json to_json(const MeshInfo& info);
std::string to_text(const MeshInfo& info);

}  // namespace rayint
