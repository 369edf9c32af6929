#pragma once
// The report of `rayint render MESHCASE --stats`: the case, the mesh, the cost of the exact
// render and (with --compare) the other method's error statistics; and the summary lines
// printed on stderr.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/render/mesh_render.hpp"

namespace rayint {

// A render compared with another method: its label and the heat map's path.
struct MeshRenderComparison {
  std::string label, heat_map;
};

nlohmann::json to_json(const MeshRenderCost& cost);
nlohmann::json mesh_render_json(const MeshCase& c, const TetTraversal& mesh, const MeshRender& r,
                                const MeshRenderComparison* compare);
// "rayint render: N rays in ..." and, when compared, "rayint render: LABEL vs exact: ...".
std::string mesh_render_summary(const MeshRender& r, const MeshRenderComparison* compare);
// The "compare" block of --stats and its summary line ("LABEL vs AGAINST: max rel ..."), shared
// by the tetrahedral and the own-cells renders.
nlohmann::json comparison_json(const MeshRenderComparison& compare, const ErrorSummary& e);
std::string comparison_summary(const MeshRenderComparison& compare, const ErrorSummary& e, const char* against);

}  // namespace rayint
