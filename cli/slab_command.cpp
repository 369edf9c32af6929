// rayint slab -- the plane-parallel slab (src/rayint/scattering/slab.hpp): either one problem
// given by options, or every value of a published benchmark file (--benchmark), solved by the
// adding-doubling method, by Monte Carlo, (isotropic problems) by the integral equation for
// the source function, and (--method pn, one problem or a scene) by P_N. A table or JSON; exit 1
// if a benchmark value is
// not reproduced under the acceptance rule of slab_benchmark.hpp.
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rayint/core/limits.hpp"
#include "options.hpp"
#include "shard.hpp"
#include "rayint/core/error.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/input/slab_benchmark_reader.hpp"
#include "rayint/input/slab_scene_reader.hpp"
#include "rayint/report/slab_benchmark_report.hpp"
#include "rayint/report/slab_run_json.hpp"
#include "rayint/scattering/slab_run.hpp"

namespace rayint::cli {
namespace {

struct SlabOptions {
  std::string benchmark;
  std::string scene;
  std::vector<std::string> problems;
  std::string method = "both";
  BenchmarkRunOptions run;  // photons, seed, threads, streams, start thickness, IE segments, mc_max_rel
  bool no_richardson = false;
  bool no_integral_equation = false;
  bool mc_analog = false;
  bool json = false;
  bool quiet = false;
  std::string output;
  // one problem
  double tau = 1, albedo = 1, mu0 = 1, ground_albedo = 0;
  std::string phase = "isotropic", source = "beam";
  std::vector<double> mu_up, mu_down;
  int max_order = 0;
  std::string shard;  // --shard I/N
};

PhaseFunction parse_phase(const std::string& text) {
  if (text == "isotropic") return PhaseFunction::isotropic();
  if (text == "lambert") return PhaseFunction::lambert_sphere();
  if (text.rfind("hg:", 0) == 0) {
    char* end = nullptr;
    const double g = std::strtod(text.c_str() + 3, &end);
    if (end != text.c_str() + text.size() || text.size() == 3 || !(std::fabs(g) < 1))
      throw std::invalid_argument("--phase: hg:G needs |G| < 1, got '" + text + "'");
    return PhaseFunction::henyey_greenstein(g);
  }
  throw std::invalid_argument("--phase: expected isotropic, lambert or hg:G, got '" + text + "'");
}

// --method: a comma-separated list of doubling, monte_carlo, both (the two) and
// pn[:order=N][:bc=marshak|mark] (N odd in [1, kPnMaxOrder], default 15; Marshak by default).
struct SlabMethods {
  bool doubling = false, monte_carlo = false, pn = false;
  PnOptions pn_options;
};

SlabMethods parse_slab_methods(const std::string& text) {
  SlabMethods m;
  const std::string expected = "expected doubling, monte_carlo, both or pn[:order=N][:bc=marshak|mark]";
  std::stringstream list(text);
  std::string item;
  bool any = false;
  while (std::getline(list, item, ',')) {
    std::stringstream parts(item);
    std::string name, part;
    std::getline(parts, name, ':');
    any = true;
    if (name == "doubling" || name == "both") m.doubling = true;
    if (name == "monte_carlo" || name == "both") m.monte_carlo = true;
    if (name == "pn") m.pn = true;
    if (name != "doubling" && name != "monte_carlo" && name != "both" && name != "pn")
      throw std::invalid_argument("--method: " + expected + ", got '" + item + "'");
    while (std::getline(parts, part, ':')) {
      const auto eq = part.find('=');
      const std::string key = eq == std::string::npos ? part : part.substr(0, eq);
      const std::string value = eq == std::string::npos ? "" : part.substr(eq + 1);
      if (name != "pn")
        throw std::invalid_argument("--method: " + name + " takes no parameters, got '" + item + "'");
      if (key == "order") {
        const std::string range = "an odd integer in [1, " + std::to_string(kPnMaxOrder) + "]";
        char* end = nullptr;
        const long n = std::strtol(value.c_str(), &end, 10);
        if (value.empty() || *end != '\0' || n < 1 || n > kPnMaxOrder || n % 2 == 0)
          throw std::invalid_argument("--method pn: order must be " + range + ", got '" + value + "'");
        m.pn_options.order = static_cast<int>(n);
      } else if (key == "bc" && (value == "marshak" || value == "mark")) {
        m.pn_options.boundary = value == "mark" ? PnBoundary::mark : PnBoundary::marshak;
      } else if (key == "bc") {
        throw std::invalid_argument("--method pn: bc must be marshak or mark, got '" + value + "'");
      } else {
        throw std::invalid_argument("--method pn: unknown parameter '" + part + "' (accepted: order, bc)");
      }
    }
  }
  if (!any) throw std::invalid_argument("--method: " + expected + ", got '" + text + "'");
  return m;
}

SlabSource parse_source(const std::string& text) {
  if (text == "beam") return SlabSource::beam;
  if (text == "isotropic") return SlabSource::isotropic;
  throw std::invalid_argument("--source: expected beam or isotropic, got '" + text + "'");
}

// The solvers and their knobs, as the options set them (one problem, a scene or a benchmark).
BenchmarkRunOptions run_options(const SlabOptions& s, const SlabMethods& m) {
  BenchmarkRunOptions o = s.run;
  const bool doubling = m.doubling;
  o.doubling = doubling;
  o.monte_carlo = m.monte_carlo;
  o.pn = m.pn;
  o.pn_options = m.pn_options;
  o.doubling_options.richardson = !s.no_richardson;
  o.integral_equation = doubling && !s.no_integral_equation;
  o.mc_split = !s.mc_analog;
  return o;
}

// --shard / merge: the Monte Carlo block sums a shard records, or the merged ones a merge
// replays (one part per Monte Carlo solve, in problem order).
MonteCarloShardIO shard_io_for(const ShardSpec& shard) {
  MonteCarloShardIO io;
  io.shard = shard;
  if (!merging()) return io;
  io.mode = MonteCarloShardIO::Mode::replay;
  const ShardContext& c = shard_context();
  std::vector<std::vector<MonteCarloPart>> per_shard;
  for (std::size_t i = 0; i < c.data.size(); ++i) {
    if (c.data[i].is_null()) continue;
    const nlohmann::json& parts = c.data[i].at("monte_carlo");
    per_shard.emplace_back();
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const std::string field = "data.monte_carlo[" + std::to_string(k) + "]";
      per_shard.back().push_back(monte_carlo_part_from_json(parts[k], c.files[i], field));
      // Every shard holds exactly its blocks: no block left out or counted twice.
      const CoveredBlocks covered = covered_blocks(per_shard.back().back());
      if (!covered.contiguous)
        throw InputError(c.files[i] + ": " + field + ".nodes: the blocks are not one contiguous range");
      check_shard_band(i, per_shard.back().back().blocks, static_cast<long>(covered.range.begin),
                       static_cast<long>(covered.range.end), field + ".nodes");
    }
  }
  for (std::size_t k = 0; k < per_shard.front().size(); ++k) {
    std::vector<const MonteCarloPart*> parts;
    for (const auto& shard_parts : per_shard) {
      if (shard_parts.size() != per_shard.front().size())
        throw std::invalid_argument("merge: the shards hold different numbers of Monte Carlo solves");
      parts.push_back(&shard_parts[k]);
    }
    io.parts.push_back(merge_parts(parts));
  }
  return io;
}

nlohmann::json shard_data(const MonteCarloShardIO& io) {
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& p : io.parts) parts.push_back(to_json(p));
  return {{"monte_carlo", parts}};
}

}  // namespace

void set_slab_command(CLI::App& app) {
  auto s = std::make_shared<SlabOptions>();
  CLI::App* cmd = app.add_subcommand(
      "slab", "Plane-parallel slab multiple scattering: one problem, or a published benchmark file");
  cmd->add_option("--benchmark", s->benchmark,
                  "benchmark file (cases/scattering/disort_slab.json): check every value");
  cmd->add_option("--scene", s->scene,
                  "slab scene file (medium type \"slab\", beam or isotropic light, detectors; "
                  "docs/multiple-scattering.md): solve it");
  cmd->add_option("--problems", s->problems, "benchmark: only these problem ids (e.g. 1a,3b)")
      ->delimiter(',');
  cmd->add_option("--method", s->method,
                  "comma-separated: doubling, monte_carlo, both (default), "
                  "pn[:order=N][:bc=marshak|mark] (P_N, N odd <= 127, default 15; P1 is the "
                  "diffusion approximation); pn on one problem or a scene only");
  cmd->add_option("--photons", s->run.mc_options.photons, "Monte Carlo photons per problem (default 1e6)");
  cmd->add_option("--seed", s->run.mc_options.seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--threads", s->run.mc_options.threads, "threads (default: all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--streams", s->run.doubling_options.streams, "doubling: Gauss cosines per hemisphere (default 64)");
  cmd->add_option("--start-thickness", s->run.doubling_options.start_thickness,
                  "doubling: largest optical thickness of the single-scattering start layer (1e-8)");
  cmd->add_flag("--no-richardson", s->no_richardson,
                "doubling: no extrapolation in the start thickness (for convergence studies)");
  cmd->add_flag("--no-integral-equation", s->no_integral_equation,
                "no integral-equation solver (isotropic problems; it runs with the doubling)");
  cmd->add_option("--ie-segments", s->run.ie_options.segments,
                  "integral equation: coarsest mesh segments (default 128; meshes x1, x2, x4, x8)");
  cmd->add_option("--mc-max-rel", s->run.mc_max_rel,
                  "benchmark: largest 4 SE / published a Monte Carlo check may have (default 0.02)");
  cmd->add_flag("--mc-analog", s->mc_analog,
                "Monte Carlo of every order (default: exact orders 0-1 plus Monte Carlo of orders >= 2)");
  cmd->add_flag("--json", s->json, "benchmark: JSON instead of a table");
  add_quiet_flag(cmd, s->quiet);
  add_output_option(cmd, s->output, "write the result here (atomically) instead of stdout");
  add_shard_option(cmd, s->shard);
  cmd->add_option("--tau", s->tau, "one problem: optical thickness");
  cmd->add_option("--albedo", s->albedo, "one problem: single-scattering albedo");
  cmd->add_option("--ground-albedo", s->ground_albedo,
                  "one problem: albedo of a Lambertian ground below the slab (default 0: black); "
                  "doubling, pn, analog Monte Carlo");
  cmd->add_option("--phase", s->phase, "one problem: isotropic, lambert or hg:G");
  cmd->add_option("--source", s->source, "one problem: beam or isotropic");
  cmd->add_option("--mu0", s->mu0, "one problem: beam cosine");
  cmd->add_option("--mu-up", s->mu_up, "one problem: reflected-intensity cosines")->delimiter(',');
  cmd->add_option("--mu-down", s->mu_down, "one problem: transmitted-intensity cosines")->delimiter(',');
  cmd->add_option("--max-order", s->max_order,
                  "one problem: Monte Carlo scattering orders (1: single scattering, compared "
                  "with the closed form)");
  cmd->callback([s]() {
    const SlabMethods methods = parse_slab_methods(s->method);
    if (methods.pn && !s->benchmark.empty())
      throw std::invalid_argument("--method pn: runs on one problem or a --scene, not on --benchmark "
                                  "(reports/scattering/pn_report.py compares it with the published values)");
    if (methods.pn && s->max_order != 0)
      throw std::invalid_argument("--max-order: P_N solves every order; give it without pn");
    if (s->run.mc_options.photons < 1) throw std::invalid_argument("--photons: must be >= 1");
    limits::check(limits::kPhotons, static_cast<double>(s->run.mc_options.photons), "--photons");
    if (s->run.doubling_options.streams < 2 || s->run.doubling_options.streams > 1024) throw std::invalid_argument("--streams: must be in [2, 1024]");
    if (!(s->run.doubling_options.start_thickness > 0 && s->run.doubling_options.start_thickness <= 1e-3))
      throw std::invalid_argument("--start-thickness: must be in (0, 1e-3]");
    if (s->run.ie_options.segments < 4 || s->run.ie_options.segments > 512)
      throw std::invalid_argument("--ie-segments: must be in [4, 512]");
    if (!(s->run.mc_max_rel > 0)) throw std::invalid_argument("--mc-max-rel: must be > 0");
    if (s->max_order < 0) throw std::invalid_argument("--max-order: must be >= 0");
    if (!s->scene.empty() && !s->benchmark.empty())
      throw std::invalid_argument("--scene and --benchmark: give one of them");
    BenchmarkRunOptions o = run_options(*s, methods);
    if (!s->scene.empty() || s->benchmark.empty()) o.mc_options.max_order = s->max_order;  // not a benchmark's
    // Shards: every solver runs as in the single run, but the Monte Carlo only over the shard's
    // blocks (or, merging, from the shards' block sums); the deterministic solvers run again.
    const bool in_shard = !s->shard.empty();
    const ShardSpec shard = begin_shard(s->shard, s->output);
    std::vector<std::string> inputs;
    for (const auto* f : {&s->benchmark, &s->scene})
      if (!f->empty()) inputs.push_back(*f);
    if (merging()) check_merge_inputs("slab", inputs);
    MonteCarloShardIO io = shard_io_for(shard);
    if (in_shard || merging()) o.mc_options.shard_io = &io;
    const auto finish = [&](const std::string& report) {
      if (in_shard)
        write_shard(s->output, "slab", shard, inputs, shard_data(io));
      else
        emit(report, s->output);
    };
    if (!s->scene.empty()) {
      const SlabScene scene = read_slab_scene(s->scene);
      if (!scene.legendre.empty()) {
        if (methods.doubling || methods.monte_carlo)
          throw std::invalid_argument(s->scene + ": phase.type: a " + scene.phase_name +
                                      " phase function is solved by --method pn only");
        o.pn_options.legendre = scene.legendre;
      }
      const SlabRun run = run_slab_problem(scene.problem, o);
      nlohmann::json j = slab_scene_json(s->scene, scene.name, scene.problem);
      j["phase"] = scene.phase_name;
      if (!scene.legendre.empty()) {
        j["phase_legendre_terms"] = scene.legendre.size();
        j["phase_mean_cosine"] = scene.legendre.size() > 1 ? scene.legendre[1] : 0.0;
      }
      finish(slab_run_json(j, run).dump(2));
      return;
    }
    if (s->benchmark.empty()) {
      SlabProblem p;
      p.tau = s->tau;
      p.albedo = s->albedo;
      p.phase = parse_phase(s->phase);
      p.source = parse_source(s->source);
      p.mu0 = s->mu0;
      p.mu_up = s->mu_up;
      p.mu_down = s->mu_down;
      p.ground_albedo = s->ground_albedo;
      if (!(p.ground_albedo >= 0 && p.ground_albedo <= 1))
        throw std::invalid_argument("--ground-albedo: must be in [0, 1]");
      validate(p);
      const SlabRun run = run_slab_problem(p, o);
      finish(slab_run_json(slab_problem_json(p, s->phase, s->source), run).dump(2));
      return;
    }
    SlabBenchmark b = read_slab_benchmark(s->benchmark);
    try {
      select_benchmark_problems(b, s->problems, s->benchmark);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--problems: ") + e.what());
    }
    const bool quiet = s->quiet;
    const BenchmarkReport r = run_slab_benchmark(b, o, [quiet](const std::string& id) {
      if (!quiet) std::cerr << "rayint slab: problem " << id << "\n";
    });
    finish(s->json ? slab_benchmark_json(b, r, o).dump(2) : slab_benchmark_table(r, o));
    if (!r.all_pass() && !in_shard) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
