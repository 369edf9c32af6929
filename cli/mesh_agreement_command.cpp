// rayint mesh-agreement [--rays N] [--seed S] [--n N] -- the issue-5 target measured: on a field
// linear over the whole mesh, the mesh path (traversal + Eq. 9/13 + exact) against one exact
// segment through the box (src/rayint/accuracy/mesh_agreement.hpp; the [mesh] test runs the
// same function with the defaults).
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "rayint/accuracy/mesh_agreement.hpp"

namespace rayint::cli {

void set_mesh_agreement_command(CLI::App& app) {
  auto opt = std::make_shared<MeshAgreementOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-agreement", "Mesh path vs. one exact segment on a globally linear field (random rays)");
  cmd->add_option("--rays", opt->rays, "number of random rays")->check(CLI::Range(1, 100000000));
  cmd->add_option("--seed", opt->seed, "random seed");
  cmd->add_option("--n", opt->n, "linear-box resolution (6 (2n)^3 tets)")->check(CLI::Range(1, 60));
  cmd->add_option("-o,--output", *out, "write the JSON here instead of stdout");
  cmd->callback([opt, out] {
    const MeshAgreement a = measure_linear_field_agreement(*opt);
    const nlohmann::json j = {{"rays", a.rays}, {"seed", opt->seed}, {"n", opt->n}, {"tets", a.tets},
                              {"hits", a.hits}, {"segments", a.segments}, {"max_rel_error", a.max_rel},
                              {"max_length_error", a.max_length_abs}, {"budget_exhausted", a.budget_exhausted}};
    emit(j.dump(2), *out);
  });
}

}  // namespace rayint::cli
