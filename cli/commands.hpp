#pragma once
// One file per subcommand; each registers its options on the app and calls the library.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"

namespace rayint::cli {

// Exit codes (docs/exit-codes.md): 0 success, 1 a check or gate failed or a method failed on
// some ray (output written, the failures marked), 2 bad input or usage (nothing written), or an
// output (a file or standard output) that could not be written completely.
inline constexpr int kExitFailed = 1;
inline constexpr int kExitBadInput = 2;

// Thrown by a subcommand whose check or gate failed after its output was written; main()
// turns it into kExitFailed, so destructors run and output is flushed.
struct ChecksFailed {};

void set_eval_command(CLI::App& app);    // eval_command.cpp
void set_bench_command(CLI::App& app);   // bench_command.cpp
void set_stress_command(CLI::App& app);  // stress_command.cpp
void set_gate_command(CLI::App& app);    // gate_command.cpp
void set_check_command(CLI::App& app);   // check_command.cpp
void set_render_command(CLI::App& app);  // render_command.cpp
void set_scene_sweep_command(CLI::App& app);  // scene_sweep_command.cpp
void set_generate_mesh_command(CLI::App& app);  // generate_mesh_command.cpp
void set_mesh_agreement_command(CLI::App& app);  // mesh_agreement_command.cpp
void set_cells_command(CLI::App& app);   // cells_command.cpp
void set_slab_command(CLI::App& app);    // slab_command.cpp
void set_scatter_command(CLI::App& app);  // scatter_command.cpp
void set_tf_command(CLI::App& app);       // tf_command.cpp
void set_methods_command(CLI::App& app);  // methods_command.cpp
void set_mesh_command(CLI::App& app);     // mesh_command.cpp
void set_grad_command(CLI::App& app);     // grad_command.cpp
void set_gradcheck_command(CLI::App& app);  // gradcheck_command.cpp
void set_converge_command(CLI::App& app);  // converge_command.cpp

// A --methods value: parse_method_list with the option named in the message, e.g.
// "--methods riemann:n=0: n must be an integer >= 1" (MethodSpecError).
std::vector<MethodSpec> parse_methods_option(const std::string& csv,
                                             const std::string& option = "--methods");

// Prints `text` to stdout, or writes it atomically to `path` when non-empty.
void emit(const std::string& text, const std::string& path);

}  // namespace rayint::cli
