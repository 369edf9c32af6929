// rayint generate-mesh KIND -o FILE.vtk -- the generated meshes of cases/meshes/ (analytic
// fields; see src/rayint/mesh/mesh_generators.hpp), written as VTK legacy files.
#include <memory>
#include <string>

#include "commands.hpp"
#include "rayint/report/vtk_legacy_writer.hpp"
#include "rayint/mesh/mesh_generators.hpp"

namespace rayint::cli {

void set_generate_mesh_command(CLI::App& app) {
  struct Options {
    std::string kind, output;
    int n = 4;
    std::uint64_t seed = 1;
    bool ascii = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("generate-mesh", "Write a generated tetrahedral mesh with an analytic field (VTK legacy)");
  cmd->add_option("kind", opt->kind, "ball | linear-box | ring")->required()->check(CLI::IsMember(generated_mesh_kinds()));
  cmd->add_option("-o,--output", opt->output, "the .vtk file to write")->required();
  cmd->add_option("--n", opt->n, "resolution: cells per unit edge of the underlying grid (1-200)")->check(CLI::Range(1, 200));
  cmd->add_option("--seed", opt->seed, "seed of the jitter (linear-box)");
  cmd->add_flag("--ascii", opt->ascii, "ASCII instead of big-endian binary");
  cmd->callback([opt] {
    const GeneratedMesh g = generate_mesh(opt->kind, opt->n, opt->seed);
    VtkWriteOptions w;
    w.encoding = opt->ascii ? VtkEncoding::ascii : VtkEncoding::binary;
    w.title = g.description;
    w.scalar_name = "s";
    write_vtk_legacy(opt->output, g.mesh, w);
  });
}

}  // namespace rayint::cli
