#pragma once
// The data a shard file carries (`--shard I/N`, README "Shards and merge"), as JSON; read back
// by input/shard_reader.hpp. Doubles are written so that they read back bit for bit: finite
// ones as JSON numbers (nlohmann writes the shortest round-trip form), +-inf and NaN as the
// strings "inf", "-inf", "nan".
#include <nlohmann/json.hpp>

#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/render/mesh_render.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/scattering/volume_comparison.hpp"
#include "rayint/scene/pipeline.hpp"
#include "rayint/studies/cells_study.hpp"
#include "rayint/studies/stress.hpp"
#include "rayint/studies/sweep.hpp"

namespace rayint {

nlohmann::json exact_json(double x);

// {"blocks", "scores", "collisions", "seconds", "nodes": [[level, index, n, [sum...], [sum2...]], ...]}
nlohmann::json to_json(const MonteCarloPart& part);
nlohmann::json to_json(const StressPartial& partial);
nlohmann::json to_json(const MeshRenderPart& part);
// The own mode's band: {"mode": "own", "width", "height", "row_begin", "row_end", "compared",
// "image", "failed" (0/1 per pixel), ["compared_image", "rel_error"], "counts": [failed_pixels,
// rays, chords], "max_error_estimate", "seconds": [wall, traversal, integration], "threads",
// "traversal": [7 counts of CellTraversalStats]}
nlohmann::json to_json(const CellMeshRenderPart& part);
// {"width", "height", "lines", "line_begin", "line_end", "terms", "pixels", "ray_terms",
// "line_sums" (flat RGB triples), "work": [[seconds, cpu_seconds, setup_seconds,
// setup_cpu_seconds, rays, samples, shadow_rays, shadow_samples, lookups] per term, then
// shadows], "render_seconds", "render_cpu_seconds", "setup_seconds", "setup_cpu_seconds", "threads"}
nlohmann::json to_json(const SceneRenderPart& part);
// {"cells": [[sample...] per type], "voxels": [[sample...] per grid], "seconds"}; a cell sample is
// {"level_error", "level_segments", "level_decompose_s", "level_exact_s", "ode": [error, s, steps],
// "reference": [s, pieces, bound_rel]}, a voxel sample [error, segments, exact_s, reference_s].
nlohmann::json to_json(const CellsSamples& part);
// {"run": {...}, "methods": [[setting...] per axis]}; a setting {"wall_seconds", "cases": [{"first_ray",
// "covered", "setup_seconds", "rays": [ray...], and "setup_failure" if it failed}]}; a ray
// [nonfinite bits, error r, error g, error b, seconds] or {"failure": message}.
nlohmann::json to_json(const SweepPart& part);
// {"width", "height", "row_begin", "row_end", "reference_all", "reference_single" (each {"mean",
// "std_error", "stats": [paths, real, tentative, shadow rays, seconds]}), "runs": [{"index",
// "method", "grid", "bins", "iterations", "converged", "setup_seconds", "gather_seconds", "image"}]}
nlohmann::json to_json(const VolumeComparisonPart& part);

}  // namespace rayint
