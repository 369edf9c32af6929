#pragma once
// JSON and summary lines of the own-interpolation outputs ("mode": "own",
// mesh/cell_traversal.hpp): `rayint render` stats and the one-line summary on stderr, `rayint
// eval` results.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace rayint {

// {"mode": "own", "cells": {"hexahedron": n, ...}, "points", "boundary_faces", "faces"}
nlohmann::json own_cells_json(const CellTraversal& mesh);
nlohmann::json to_json(const CellTraversalStats& s);
nlohmann::json cell_mesh_render_json(const MeshCase& mc, const CellTraversal& mesh, const CellMeshRender& r);
std::string cell_mesh_render_summary(const CellMeshRender& r);

// `rayint eval` in the own mode: {"mode": "own", "cases": [...]}; a failed ray's values and
// error are null, with its failure text; with_reference false: no reference or error fields.
nlohmann::json own_eval_json(const std::vector<OwnCaseEvaluation>& cases, bool with_reference);
std::string own_eval_table(const std::vector<OwnCaseEvaluation>& cases, bool with_reference);

}  // namespace rayint
