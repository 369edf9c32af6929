// `rayint scene-sweep SCENE.json --config EFFECT=METHOD[,EFFECT=METHOD...] ... --errors K`:
// error against cost of method configurations on one scene, references computed once
// (scene/scene_sweep.hpp). JSON to stdout or -o.
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "progress.hpp"
#include "options.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/report/scene_sweep_json.hpp"
#include "rayint/scene/effect.hpp"
#include "rayint/scene/scene_sweep.hpp"

namespace rayint::cli {

void set_scene_sweep_command(CLI::App& app) {
  struct Options {
    std::string input, output;
    std::vector<std::string> configs;
    int errors = 8;
    unsigned threads = 0;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("scene-sweep", "Error against cost of method configurations on a scene");
  cmd->add_option("scene", opt->input, "scene JSON")->required();
  cmd->add_option("--config", opt->configs,
                  "EFFECT=METHOD[,EFFECT=METHOD...], one configuration (repeatable)")->required();
  cmd->add_option("--errors", opt->errors, "compare on K x K pixels")->check(CLI::Range(1, 4096));
  add_threads_option(cmd, opt->threads, "worker threads (0: all cores)");
  add_output_option(cmd, opt->output, "write the JSON here (default: stdout)");
  add_quiet_flag(cmd, opt->quiet);
  cmd->callback([opt] {
    const Scene scene = read_scene_file(opt->input);
    std::vector<std::map<std::string, MethodSpec>> configs;
    for (const std::string& text : opt->configs) {
      std::map<std::string, MethodSpec> c;
      std::stringstream in(text);
      std::string item;
      while (std::getline(in, item, ',')) {
        try {
          auto [effect, spec] = parse_effect_assignment(scene, item);
          c[effect] = spec;
        } catch (const EffectMethodError& e) {
          if (e.kind == EffectMethodError::Kind::method)
            throw InputError("--config " + text + ": " + e.what());
          throw InputError("--config " + text + ": " + (e.effect.empty() ? item : e.effect) +
                           " is not an effect named in " + opt->input);
        }
      }
      configs.push_back(c);
    }
    ProgressLine progress_line;
    const SceneSweepResult r = sweep_scene(scene, configs, opt->errors, opt->threads,
                                      [opt, &progress_line](std::size_t done, std::size_t total) {
                                        if (!opt->quiet)
                                          progress_line.update("configuration " + std::to_string(done) + "/" +
                                                                   std::to_string(total),
                                                               static_cast<double>(done) / static_cast<double>(total));
                                      });
    if (!opt->quiet) progress_line.finish();
    emit(scene_sweep_json(scene, r).dump(2) + "\n", opt->output);
  });
}

}  // namespace rayint::cli
