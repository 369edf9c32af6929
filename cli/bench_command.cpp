// rayint bench [CASES...] -- the accuracy/cost sweep (studies/sweep.hpp): every method along its
// knob, error against the 50-digit reference and time per ray, written as JSON
// (reports/bench.json by default; reports/make_report.py turns it into plots and a README).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "subcommand.hpp"
#include "options.hpp"
#include "shard.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/studies/own_split_bench.hpp"
#include "rayint/studies/sweep.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/sweep_json.hpp"
#include "rayint/report/sweep_table.hpp"

namespace rayint::cli {
namespace {

// The case files named on the command line (a folder means every case file in it), or every
// case of ./cases when none is named.
std::vector<std::string> case_files(const std::vector<std::string>& args) {
  if (args.empty() && !std::filesystem::is_directory("cases"))
    throw InputError("bench: no case files given and no cases/ folder in " +
                     std::filesystem::current_path().string());
  std::vector<std::string> files;
  for (const auto& a : args.empty() ? std::vector<std::string>{"cases"} : args) {
    if (std::filesystem::is_directory(a)) {
      for (const auto& f : list_case_files(a)) files.push_back(f);
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) throw InputError("bench: no case files found");
  return files;
}

std::vector<std::string> split_names(const std::string& csv) {
  std::vector<std::string> out;
  std::stringstream in(csv);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty()) continue;
    if (item.find(':') != std::string::npos)
      throw std::invalid_argument(
          "bench: --methods takes method names (the sweep chooses the "
          "settings), got '" +
          item + "'");
    out.push_back(item);
  }
  return out;
}

}  // namespace

void set_bench_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> files;
    std::string methods;
    std::string output = "bench.json";  // the committed reports/bench.json only by scripts/report.sh
    SweepOptions sweep;
    bool quiet = false;
    MeshReadOptions mesh;
    std::string shard;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = add_command(
      app, "bench", "Accuracy/cost sweep: every method along its knob, error and time per ray",
      "0 the report was written (a setting that failed on some rays is counted in "
      "it: failed_rays, null errors where no ray ran, a failed: line per method); 2 bad input.");
  cmd->add_option("cases", opt->files,
                  "Case files (JSON) or folders of them; default: the folder cases/");
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated method names to sweep (default: all; exact always runs)");
  cmd->add_option(
         "--max-seconds", opt->sweep.max_seconds,
         "Budget in seconds for measuring all settings, after the references; exact always "
         "runs in full (0 = none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--method-seconds", opt->sweep.method_max_seconds, "The same budget per method (0 = none)")
      ->check(CLI::NonNegativeNumber);
  CLI::Option* output_option = cmd->add_option("-o,--output", opt->output, "JSON output file ('-' = stdout)")
      ->capture_default_str();
  cmd->add_option("--batches", opt->sweep.timing.timing_batches,
                  "Timing batches per ray (median taken); for a mesh of cells other than tetrahedra: "
                  "repetitions of the whole ray set, own and split")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--batch-seconds", opt->sweep.timing.timing_batch_seconds, "Minimum length of one timing batch")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  add_threads_option(cmd, opt->sweep.timing.threads, "Threads for the reference (0 = all cores)");
  add_quiet_flag(cmd, opt->quiet);
  add_strict_mesh_flag(cmd, opt->mesh.strict);
  add_cells_option(cmd, opt->mesh.split_cells);
  add_shard_option(cmd, opt->shard);
  cmd->callback([opt, output_option] {
    const std::vector<SweepAxis> axes = select_sweep_axes(split_names(opt->methods));
    const std::vector<std::string> files = case_files(opt->files);
    std::vector<Case> cases;
    // Mesh cases of cells other than tetrahedra (without --cells split): no segments to sweep;
    // their own interpolation is timed against VTK's split instead (studies/own_split_bench.hpp).
    std::vector<MeshCase> own_cases;
    const json_source::InputFileLog read;  // the case files and the meshes they name: shard inputs
    for (const auto& f : files) {  // validate all first
      std::optional<MeshCase> own;
      Case c = read_case_file(f, opt->mesh, nullptr, &own);
      if (own) {
        own_cases.push_back(std::move(*own));
      } else {
        cases.push_back(std::move(c));
      }
    }
    if (!own_cases.empty() && (!opt->shard.empty() || merging()))
      throw InputError(own_cases.front().source + ": mesh_file: cells other than tetrahedra (own interpolation vs "
                       "split timing) cannot be sharded or merged; run bench on them without --shard");
    const std::vector<std::string> inputs = run_inputs(files, read);
    if (opt->output != "-") {
      const auto parent = std::filesystem::path(opt->output).parent_path();
      if (!parent.empty()) std::filesystem::create_directories(parent);
    }
    SweepOptions so = opt->sweep;
    if (!opt->quiet)
      so.progress = [](const SweepProgress& p) { std::cerr << sweep_progress_line(p) << std::flush; };
    // --shard: every setting on this shard's rays, what each ray measured to the shard file;
    // merge: the report from the shards' rays (README, "Shards and merge").
    const bool in_shard = !opt->shard.empty();
    const ShardSpec shard = begin_shard(opt->shard, opt->output);
    if (in_shard) {
      if (output_option->count() == 0)
        throw std::invalid_argument("--shard: needs -o FILE for the shard file");
      write_shard(opt->output, "bench", shard, inputs, to_json(run_sweep_part(cases, axes, so, shard)));
      return;
    }
    OwnSplitRun own_run;
    if (!own_cases.empty()) {
      OwnSplitBenchOptions oo;
      oo.repetitions = opt->sweep.timing.timing_batches;
      own_run = bench_own_cases(own_cases, oo);
    }
    if (cases.empty()) {  // only own-interpolation cases: nothing to sweep
      emit(own_split_report_json(own_run).dump(1), opt->output);
      if (opt->output != "-") {
        std::cout << own_split_table(own_run);
        std::cout << "wrote " << opt->output << "\n";
      }
      return;
    }
    SweepResult result;
    if (merging()) {
      // every case's rays exactly once: each setting of each part holds its shard's band
      const auto check = [&cases](std::size_t i, const SweepPart& part) {
        const std::vector<IndexRange> want = sweep_shard_rays(cases, merged_shard(i));
        for (std::size_t a = 0; a < part.methods.size(); ++a)
          for (std::size_t k = 0; k < part.methods[a].size(); ++k) {
            const auto& got = part.methods[a][k].cases;
            const std::string where = "data.methods[" + std::to_string(a) + "][" + std::to_string(k) + "]";
            check_shard_count(i, want.size(), got.size(), where + ".cases (cases)");
            for (std::size_t ci = 0; ci < want.size(); ++ci)
              if (want[ci].size() > 0 || got[ci].covered > 0)
                check_shard_cover(i, want[ci].begin, want[ci].end, static_cast<long>(got[ci].first_ray),
                                 static_cast<long>(got[ci].first_ray + got[ci].covered),
                                 where + ".cases[" + std::to_string(ci) + "].first_ray");
          }
      };
      result = finish_sweep(cases, axes, so, merged_parts("bench", inputs, sweep_part_from_json, check));
    } else {
      result = run_sweep(cases, axes, so);
    }
    nlohmann::json report = sweep_report_json(result);
    if (!own_cases.empty()) report["own_vs_split"] = own_split_json(own_run);
    emit(report.dump(1), opt->output);
    if (opt->output != "-") {
      std::cout << sweep_targets_table(result);
      if (!own_cases.empty()) std::cout << own_split_table(own_run);
      std::cout << "wrote " << opt->output << "\n";
    }
  });
}

}  // namespace rayint::cli
