#include <stdexcept>

#include "commands.hpp"

namespace rayint::cli {

void set_stress_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("stress", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("rayint stress is not implemented yet"); });
}

}  // namespace rayint::cli
