// rayint -- numerical verification of the ray integrals of direct volume rendering.
#include <iostream>

#include "commands.hpp"
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

}  // namespace rayint::cli

int main(int argc, char** argv) {
  rayint::register_standard_effects();  // multiple_scattering (scene/effect.hpp)
#ifdef RAYINT_WITH_VTK
  rayint::register_vtk_methods();  // vtk_linear, vtk_partial_preint, vtk_preint, vtk_homogeneous
  rayint::register_vtk_mesh_readers();  // mesh_file .vtu, .pvtu
#endif
  CLI::App app{"rayint: how far is a ray integration from the truth, and what does it cost"};
  app.require_subcommand(1);
  rayint::cli::set_eval_command(app);
  rayint::cli::set_bench_command(app);
  rayint::cli::set_stress_command(app);
  rayint::cli::set_gate_command(app);
  rayint::cli::set_check_command(app);
  rayint::cli::set_render_command(app);
  rayint::cli::set_scene_sweep_command(app);
  rayint::cli::set_generate_mesh_command(app);
  rayint::cli::set_mesh_agreement_command(app);
  rayint::cli::set_cells_command(app);
  rayint::cli::set_slab_command(app);
  rayint::cli::set_scatter_command(app);
  rayint::cli::set_tf_command(app);
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
