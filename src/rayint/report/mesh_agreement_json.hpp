#pragma once
// The report of `rayint mesh-agreement`: the linear-field agreement and the vertex-ray chords
// (studies/mesh_agreement.hpp).
#include <nlohmann/json.hpp>

#include "rayint/studies/mesh_agreement.hpp"

namespace rayint {

// `grid`: cubes per edge of the structured mesh the vertex rays ran through.
nlohmann::json mesh_agreement_json(const MeshAgreementOptions& options, const MeshAgreement& linear,
                                   int grid, const VertexRayChords& vertex);

}  // namespace rayint
