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

}  // namespace rayint::cli
