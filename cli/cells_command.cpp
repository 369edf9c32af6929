// rayint cells -- higher-order cells (tet10, hex8, hex20) and voxel grids: the error of
// decomposing them into linear tetrahedra and integrating with `exact`, per subdivision level,
// and of the polynomial-scalar ODE, against the 50-digit polynomial reference
// (src/rayint/studies/cells_study.hpp). JSON on stdout or to -o (then a table on stdout);
// progress on stderr.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "rayint/studies/cells_study.hpp"
#include "rayint/report/cells_json.hpp"

namespace rayint::cli {
namespace {

std::string g3(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string format_table(const CellsReport& r) {
  const CellsStudyOptions& o = r.options;
  std::string out = "rayint cells: seed " + std::to_string(o.seed) + ", " +
                    std::to_string(o.count) + " cells per type x " +
                    std::to_string(o.rays_per_cell) + " rays; error = max relative error of the "
                    "intensity over r, g, b, against the 50-digit polynomial reference\n\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-6s %-10s %10s %10s %10s %10s %10s %10s\n", "cell",
                "method", "max rel", "p99 rel", "med rel", "segments", "us/ray", "");
  out += line;
  for (const auto& c : r.cells) {
    for (const auto& l : c.levels) {
      std::snprintf(line, sizeof line, "%-6s %-10s %10s %10s %10s %10.1f %10.1f\n", c.type.c_str(),
                    ("tets n=" + std::to_string(l.level)).c_str(), g3(l.rel.max).c_str(),
                    g3(l.rel.p99).c_str(), g3(l.rel.median).c_str(), l.segments_per_ray,
                    l.decompose_us_per_ray + l.exact_us_per_ray);
      out += line;
    }
    std::snprintf(line, sizeof line, "%-6s %-10s %10s %10s %10s %10.1f %10.1f\n", c.type.c_str(),
                  "ode", g3(c.ode_rel.max).c_str(), g3(c.ode_rel.p99).c_str(),
                  g3(c.ode_rel.median).c_str(), c.ode_steps_per_ray, c.ode_us_per_ray);
    out += line;
    std::string steps;
    for (double s : c.order_steps) steps += (steps.empty() ? "" : ", ") + g3(s);
    out += "       order of the tets' error: median fit " + g3(c.order_median) + ", max fit " +
           g3(c.order_max) + ", per doubling " + steps + "; reference " +
           g3(c.reference_ms_per_ray) + " ms/ray, " + g3(c.pieces_per_ray) +
           " pieces/ray, bound <= " + g3(c.max_reference_bound_rel) + "\n";
  }
  out += "\nvoxel grids: Kuhn tetrahedra + exact against the trilinear interpolant (reference)\n";
  std::snprintf(line, sizeof line, "%-8s %8s %6s %10s %10s %10s %10s %10s %12s\n", "field",
                "points", "rays", "max rel", "p99 rel", "med rel", "segments", "us/ray",
                "ref ms/ray");
  out += line;
  for (const auto& v : r.voxels) {
    std::snprintf(line, sizeof line, "%-8s %8s %6d %10s %10s %10s %10.1f %10.1f %12.1f\n",
                  v.field.c_str(), (std::to_string(v.points_per_axis) + "^3").c_str(), v.samples,
                  g3(v.rel.max).c_str(), g3(v.rel.p99).c_str(), g3(v.rel.median).c_str(),
                  v.segments_per_ray, v.exact_us_per_ray, v.reference_ms_per_ray);
    out += line;
  }
  out += "\n(ode: segments column = accepted steps per ray; us/ray: thread CPU time per ray, "
         "tets including the decomposition; " + std::to_string(o.threads) + " thread(s), " +
         g3(r.seconds) + " s wall)\n";
  return out;
}

}  // namespace

void set_cells_command(CLI::App& app) {
  struct Options {
    CellsStudyOptions study;
    std::string output;
    bool quiet = false;
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
      ->check(CLI::Range(1e-15, 0.5))
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
  cmd->add_flag("-q,--quiet", opt->quiet, "No progress on stderr");
  cmd->callback([opt] {
    CellsStudyOptions so = opt->study;
    if (!opt->quiet) so.progress = [](const std::string& msg) { std::cerr << "cells: " << msg << "\n"; };
    const CellsReport report = run_cells_study(so);
    const std::string json_text = to_json(report).dump(2);
    if (opt->output.empty()) {
      emit(json_text, "");
    } else {
      emit(json_text, opt->output);
      emit(format_table(report), "");
    }
  });
}

}  // namespace rayint::cli
