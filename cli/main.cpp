// rayint -- numerical verification of the ray integrals of direct volume rendering.
#include <iostream>

#include "commands.hpp"
#include "shard.hpp"
#ifdef RAYINT_WITH_VTK
#include "rayint/vtk/vtk_integrators.hpp"
#include "rayint/vtk/vtk_mesh_reader.hpp"
#endif
#include "rayint/core/atomic_file.hpp"
#include "rayint/effects/standard_effects.hpp"

namespace rayint::cli {

void emit(const std::string& text, const std::string& path) {
  if (path.empty() || path == "-") {
    std::cout << text;
    if (!text.empty() && text.back() != '\n') std::cout << '\n';
  } else {
    write_file_atomically(path, (text.empty() || text.back() == '\n') ? text : text + "\n");
  }
}

// Every subcommand on `app` (main's app, and the app `rayint merge` replays a run on).
void build_app(CLI::App& app) {
  set_eval_command(app);
  set_bench_command(app);
  set_stress_command(app);
  set_gate_command(app);
  set_check_command(app);
  set_render_command(app);
  set_scene_sweep_command(app);
  set_generate_mesh_command(app);
  set_mesh_agreement_command(app);
  set_cells_command(app);
  set_slab_command(app);
  set_scatter_command(app);
  set_tf_command(app);
  set_grad_command(app), set_gradcheck_command(app);
  set_merge_command(app, build_app);
}

}  // namespace rayint::cli

int main(int argc, char** argv) {
  rayint::register_standard_effects();  // multiple_scattering (scene/effect.hpp)
#ifdef RAYINT_WITH_VTK
  rayint::register_vtk_methods();  // vtk_linear, vtk_partial_preint, vtk_preint, vtk_homogeneous
  rayint::register_vtk_mesh_readers();  // mesh_file .vtu, .pvtu
#endif
  CLI::App app{"rayint: how far is a ray integration from the truth, and what does it cost"};
  app.require_subcommand(1);
  rayint::cli::build_app(app);
  for (int i = 2; i < argc; ++i) rayint::cli::shard_context().args.push_back(argv[i]);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const rayint::cli::ChecksFailed&) {
    return rayint::cli::kExitFailed;
  } catch (const std::exception& e) {  // CLI::ParseError, InputError, std::invalid_argument, ...
    std::cerr << "rayint: error: " << e.what() << "\n";
    return rayint::cli::kExitBadInput;
  }
  return 0;
}
