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

// A shard part's reader: `j` the part's data, `source` the shard file (named in messages),
// `path` the field path of `j` in it ("data"). Every part type has one; cli/shard.hpp
// merged_parts takes it.
template <class Part>
using PartReader = Part(const nlohmann::json& j, const std::string& source,
                        const std::string& path);

PartReader<MonteCarloPart> monte_carlo_part_from_json;
PartReader<StressPartial> stress_partial_from_json;
PartReader<MeshRenderPart> mesh_render_part_from_json;
PartReader<CellMeshRenderPart> cell_mesh_render_part_from_json;
PartReader<SceneRenderPart> scene_render_part_from_json;
PartReader<SweepPart> sweep_part_from_json;
PartReader<VolumeComparisonPart> volume_comparison_part_from_json;
PartReader<CellsSamples> cells_samples_from_json;

}  // namespace rayint
