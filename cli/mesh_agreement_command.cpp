// rayint mesh-agreement [--rays N] [--seed S] [--n N] -- the issue-5 target measured: on a field
// linear over the whole mesh, the mesh path (traversal + Eq. 9/13 + exact) against one exact
// segment through the box (src/rayint/studies/mesh_agreement.hpp; the [mesh] test runs the
// same function with the defaults).
#include <array>
#include <memory>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/report/mesh_agreement_json.hpp"

namespace rayint::cli {

void set_mesh_agreement_command(CLI::App& app) {
  auto opt = std::make_shared<MeshAgreementOptions>();
  auto out = std::make_shared<std::string>();
  auto vertex = std::make_shared<std::array<int, 2>>(std::array<int, 2>{50000, 16});
  CLI::App* cmd = app.add_subcommand(
      "mesh-agreement", "Mesh path vs. one exact segment on a globally linear field (random rays)");
  cmd->add_option("--rays", opt->rays, "number of random rays")->check(CLI::Range(1, 100000000));
  cmd->add_option("--seed", opt->seed, "random seed");
  cmd->add_option("--n", opt->n, "linear-box resolution (6 (2n)^3 tets)")->check(CLI::Range(1, 60));
  cmd->add_option("--vertex-rays", (*vertex)[0], "rays through pairs of grid vertices")->check(CLI::Range(0, 100000000));
  cmd->add_option("--grid", (*vertex)[1], "cubes per edge of the structured mesh for --vertex-rays")->check(CLI::Range(1, 60));
  add_output_option(cmd, *out, "write the JSON here instead of stdout");
  cmd->callback([opt, out, vertex] {
    const MeshAgreement a = measure_linear_field_agreement(*opt);
    const VertexRayChords v = measure_vertex_ray_chords((*vertex)[1], (*vertex)[0], opt->seed);
    emit(mesh_agreement_json(*opt, a, (*vertex)[1], v).dump(2), *out);
  });
}

}  // namespace rayint::cli
