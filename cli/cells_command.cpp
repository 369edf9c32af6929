// rayint cells -- higher-order cells (tet10, hex8, hex20) and voxel grids: the error of
// decomposing them into linear tetrahedra and integrating with `exact`, per subdivision level,
// and of the polynomial-scalar ODE, against the 50-digit polynomial reference
// (src/rayint/studies/cells_study.hpp). JSON on stdout or to -o (then a table on stdout);
// progress on stderr.
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "float_range.hpp"
#include "options.hpp"
#include "shard.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/studies/cells_study.hpp"
#include "rayint/report/cells_json.hpp"
#include "rayint/report/cells_table.hpp"

namespace rayint::cli {

void set_cells_command(CLI::App& app) {
  struct Options {
    CellsStudyOptions study;
    std::string output;
    bool quiet = false;
    std::string shard;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "cells", "Higher-order cells and voxel grids: error of the linear-tetrahedra route and of "
               "the ODE against the 50-digit reference");
  cmd->add_option("--count", opt->study.count, "Random cells per type")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--seed", opt->study.seed, "Seed; the same seed gives the same errors")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--rays", opt->study.rays_per_cell, "Rays per cell")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--levels", opt->study.levels, "Sub-cells per edge (comma-separated)")
      ->delimiter(',')
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--ode-rtol", opt->study.ode_rtol, "rtol of the ODE method")
      ->check(float_range(1e-15, 0.5))
      ->capture_default_str();
  cmd->add_option("--voxel-sizes", opt->study.voxel_sizes,
                  "Points per axis of the smooth-field grids (comma-separated)")
      ->delimiter(',')
      ->check(CLI::Range(2, 256))
      ->capture_default_str();
  cmd->add_option("--voxel-rays", opt->study.voxel_rays, "Rays per voxel grid")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--threads", opt->study.threads, "Worker threads")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("-o,--output", opt->output,
                  "Write the JSON report here (then print the table on stdout)");
  add_quiet_flag(cmd, opt->quiet);
  add_shard_option(cmd, opt->shard);
  cmd->callback([opt] {
    CellsStudyOptions so = opt->study;
    if (!opt->quiet) so.progress = [](const std::string& msg) { std::cerr << "cells: " << msg << "\n"; };
    // --shard: the samples of this shard's cells and voxel rays; merge: the report from the
    // shards' samples (README, "Shards and merge").
    const bool in_shard = !opt->shard.empty();
    const ShardSpec shard = begin_shard(opt->shard, opt->output);
    if (in_shard) {
      write_shard(opt->output, "cells", shard, {}, to_json(run_cells_samples(so, shard)));
      return;
    }
    CellsReport report;
    if (merging()) {
      // every cell and voxel ray exactly once: each part holds its shard's band of them
      const auto check = [&so](std::size_t i, const CellsSamples& part) {
        const ShardSpec spec = merged_shard(i);
        const std::size_t cells = shard_range(static_cast<std::size_t>(so.count), spec).size() *
                                  static_cast<std::size_t>(so.rays_per_cell);  // every ray of the band's cells
        const std::size_t rays = shard_range(static_cast<std::size_t>(so.voxel_rays), spec).size();
        for (std::size_t t = 0; t < part.cells.size(); ++t)
          check_shard_count(i, cells, part.cells[t].size(), "data.cells[" + std::to_string(t) + "] (rays of cells)");
        for (std::size_t g = 0; g < part.voxels.size(); ++g)
          check_shard_count(i, rays, part.voxels[g].size(), "data.voxels[" + std::to_string(g) + "] (rays)");
      };
      report = finish_cells_study(so, merged_parts("cells", {}, cells_samples_from_json, check));
    } else {
      report = run_cells_study(so);
    }
    const std::string json_text = to_json(report).dump(2);
    if (opt->output.empty()) {
      emit(json_text, "");
    } else {
      emit(json_text, opt->output);
      emit(cells_table(report), "");
    }
  });
}

}  // namespace rayint::cli
