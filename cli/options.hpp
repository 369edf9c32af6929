#pragma once
// Options several subcommands register the same way.
#include <CLI/CLI.hpp>
#include <string>

namespace rayint::cli {

// --threads N, checked >= 0 (0: all cores).
template <class Int>
CLI::Option* add_threads_option(CLI::App* cmd, Int& threads,
                                const std::string& help = "Worker threads (0: all cores)") {
  return cmd->add_option("--threads", threads, help)->check(CLI::NonNegativeNumber);
}

// -q,--quiet: no progress on stderr.
inline CLI::Option* add_quiet_flag(CLI::App* cmd, bool& quiet) {
  return cmd->add_flag("-q,--quiet", quiet, "No progress on stderr");
}

// --strict-mesh: refuse inverted and degenerate tets (input/mesh_case_reader.hpp MeshReadOptions)
// instead of reorienting and dropping them.
inline CLI::Option* add_strict_mesh_flag(CLI::App* cmd, bool& strict) {
  return cmd->add_flag("--strict-mesh", strict,
                       "Mesh cases: refuse inverted, zero-volume and sliver tetrahedra (default: "
                       "reorient inverted ones, drop degenerate ones, and count both)");
}

}  // namespace rayint::cli
