#include <stdexcept>

#include "commands.hpp"

namespace rayint::cli {

void set_bench_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("bench", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("rayint bench is not implemented yet"); });
}

}  // namespace rayint::cli
