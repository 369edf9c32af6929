// rayint methods [--format text|json] -- every method with its parameters, types, defaults and
// allowed values: the table parse_method_spec validates against (integrators/registry.cpp).
#include <memory>
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/report/method_table.hpp"

namespace rayint::cli {

void set_methods_command(CLI::App& app) {
  struct Options {
    std::string format = "text";
    std::string output;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "methods", "List every method with its parameters, types, defaults and allowed values");
  cmd->add_option("--format", opt->format, "text or json")->check(CLI::IsMember({"text", "json"}));
  add_output_option(cmd, opt->output);
  cmd->callback([opt] {
    emit(opt->format == "json" ? methods_json(method_table()).dump(2) : methods_text(method_table()),
         opt->output);
  });
}

}  // namespace rayint::cli
