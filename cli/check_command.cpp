#include <stdexcept>

#include "commands.hpp"

namespace rayint::cli {

void set_check_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("check", "(not implemented yet)");
  cmd->callback([] { throw std::runtime_error("rayint check is not implemented yet"); });
}

}  // namespace rayint::cli
