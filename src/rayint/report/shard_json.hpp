#pragma once
// The data a shard file carries (`--shard I/N`, README "Shards and merge"), as JSON; read back
// by input/shard_reader.hpp. Doubles are written so that they read back bit for bit: finite
// ones as JSON numbers (nlohmann writes the shortest round-trip form), +-inf and NaN as the
// strings "inf", "-inf", "nan".
#include <nlohmann/json.hpp>

#include "rayint/render/mesh_render.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/studies/stress.hpp"

namespace rayint {

nlohmann::json exact_json(double x);

// {"blocks", "scores", "collisions", "seconds", "nodes": [[level, index, n, [sum...], [sum2...]], ...]}
nlohmann::json to_json(const MonteCarloPart& part);
nlohmann::json to_json(const StressPartial& partial);
nlohmann::json to_json(const MeshRenderPart& part);

}  // namespace rayint
