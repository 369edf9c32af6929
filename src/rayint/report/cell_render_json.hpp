#pragma once
// JSON and summary lines of the own-interpolation outputs ("mode": "own",
// mesh/cell_traversal.hpp): `rayint render` stats and the one-line summary on stderr, `rayint
// eval` results.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/report/mesh_render_json.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace rayint {

// {"dropped_zero_volume": n, "dropped_zero_volume_by_type": {"hexahedron": n, ...}}: the
// zero-volume cells the own mode dropped (mesh/cell_mesh.hpp), in eval and render --stats.
nlohmann::json zero_volume_json(long dropped, const std::map<std::string, long>& by_type);
// {"mode": "own", "cells": {"hexahedron": n, ...}, "points", "boundary_faces", "faces"}
nlohmann::json own_cells_json(const CellTraversal& mesh);
nlohmann::json to_json(const CellTraversalStats& s);
// `compare` (may be null): the --compare method's label and heat map; its error summary is r.error.
nlohmann::json cell_mesh_render_json(const MeshCase& mc, const CellTraversal& mesh, const CellMeshRender& r,
                                     const MeshRenderComparison* compare = nullptr);
std::string cell_mesh_render_summary(const CellMeshRender& r, const MeshRenderComparison* compare = nullptr);

// `rayint eval` in the own mode: {"mode": "own", "cases": [...]}; a failed ray's values and
// error are null, with its failure text; with_reference false: no reference or error fields.
nlohmann::json own_eval_json(const std::vector<OwnCaseEvaluation>& cases, bool with_reference);
std::string own_eval_table(const std::vector<OwnCaseEvaluation>& cases, bool with_reference);

}  // namespace rayint
