#pragma once
// `rayint mesh info FILE [--check]`: what a mesh file holds as rayint reads it, as JSON or as a
// few lines of text: bounds, cells by type (kept / skipped / ghost), the arrays with their
// association and components, which one is the scalar, orientation counts and, with --check, the
// overlap check (mesh/mesh_check.hpp).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

struct MeshInfo {
  std::string file;
  const TetMesh* mesh = nullptr;
  OrientationCounts orientation;
  bool checked = false;                                        // --check ran
  std::optional<std::pair<std::size_t, std::size_t>> overlap;  // its finding
  double check_seconds = 0.0;
};

nlohmann::json to_json(const MeshInfo& info);
std::string to_text(const MeshInfo& info);

}  // namespace rayint
