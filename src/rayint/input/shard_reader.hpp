#pragma once
// Reads the data of a shard file back (report/shard_json.hpp writes it). Every problem is an
// InputError "<source>: <field path>: <what>".
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/render/mesh_render.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/scattering/volume_comparison.hpp"
#include "rayint/scene/pipeline.hpp"
#include "rayint/studies/cells_study.hpp"
#include "rayint/studies/stress.hpp"
#include "rayint/studies/sweep.hpp"

namespace rayint {

MonteCarloPart monte_carlo_part_from_json(const nlohmann::json& j, const std::string& source,
                                          const std::string& path);
StressPartial stress_partial_from_json(const nlohmann::json& j, const std::string& source,
                                       const std::string& path);
MeshRenderPart mesh_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                          const std::string& path);
CellMeshRenderPart cell_mesh_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                                   const std::string& path);
SceneRenderPart scene_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                            const std::string& path);
SweepPart sweep_part_from_json(const nlohmann::json& j, const std::string& source,
                               const std::string& path);
VolumeComparisonPart volume_comparison_part_from_json(const nlohmann::json& j, const std::string& source,
                                                      const std::string& path);
CellsSamples cells_samples_from_json(const nlohmann::json& j, const std::string& source,
                                     const std::string& path);

}  // namespace rayint
