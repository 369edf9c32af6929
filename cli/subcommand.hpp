#pragma once
// A subcommand registered with what its exit statuses mean (bench, eval, gate, stress).
#include <CLI/CLI.hpp>
#include <string>

namespace rayint::cli {

// The subcommand `name` of `app`, its help ending with its exit statuses (the codes of
// docs/exit-codes.md): `exit_status` is the text after "Exit status: ", e.g. "0 ...; 1 ...; 2 bad
// input.".
inline CLI::App* add_command(CLI::App& app, const std::string& name, const std::string& description,
                             const std::string& exit_status) {
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->footer("Exit status: " + exit_status + " docs/exit-codes.md");
  return cmd;
}

}  // namespace rayint::cli
