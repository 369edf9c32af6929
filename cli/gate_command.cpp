#include <stdexcept>

#include "commands.hpp"

namespace rayint::cli {

void set_gate_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("gate", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("rayint gate is not implemented yet"); });
}

}  // namespace rayint::cli
