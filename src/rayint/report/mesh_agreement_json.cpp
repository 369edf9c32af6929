#include "rayint/report/mesh_agreement_json.hpp"

namespace rayint {

nlohmann::json mesh_agreement_json(const MeshAgreementOptions& o, const MeshAgreement& a, int grid,
                                   const VertexRayChords& v) {
  return {
      {"linear_field", {{"rays", a.rays}, {"seed", o.seed}, {"n", o.n}, {"tets", a.tets},
                        {"hits", a.hits}, {"segments", a.segments}, {"max_rel_error", a.max_rel},
                        {"max_length_error", a.max_length_abs}, {"budget_exhausted", a.budget_exhausted}}},
      {"vertex_rays", {{"rays", v.rays}, {"seed", o.seed}, {"grid", grid}, {"tets", v.tets},
                       {"max_length_error", v.max_length_abs}, {"zero_length_steps", v.zero_length_steps},
                       {"star_searches", v.star_searches}, {"budget_exhausted", v.budget_exhausted}}}};
}

}  // namespace rayint
