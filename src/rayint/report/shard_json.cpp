// Shard data as JSON (shard_json.hpp); input/shard_reader.cpp reads it back.
#include "rayint/report/shard_json.hpp"

#include <cmath>

namespace rayint {
namespace {

nlohmann::json numbers(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const double x : v) a.push_back(exact_json(x));
  return a;
}

nlohmann::json rgb(const Rgb& c) { return {exact_json(c[0]), exact_json(c[1]), exact_json(c[2])}; }

nlohmann::json pixels(const std::vector<Rgb>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const Rgb& c : v)
    for (const double x : c) a.push_back(exact_json(x));
  return a;
}

// A stats struct's counters, in the order of its counter list, as an array.
template <class Stats, std::size_t N>
nlohmann::json counters(const Stats& s, const std::array<Counter<Stats>, N>& list) {
  nlohmann::json a = nlohmann::json::array();
  for (const Counter<Stats>& c : list) a.push_back(s.*c.member);
  return a;
}

// The rows [row_begin, row_end) of a width x height image that a part holds: the mesh renders'
// bands and the volume comparison's (input/shard_reader.cpp read_rows reads them back).
template <class Part>
nlohmann::json rows_json(const Part& p) {
  return {
      {"width", p.width}, {"height", p.height}, {"row_begin", p.row_begin}, {"row_end", p.row_end}};
}

// The band both mesh renders' parts share (input/shard_reader.cpp read_band reads it back): its
// rows, the image and, when compared, the compared image and per-pixel errors.
template <class Part>
nlohmann::json band_json(const Part& p) {
  nlohmann::json j = rows_json(p);
  j["compared"] = p.compared;
  j["image"] = pixels(p.image);
  if (p.compared) {
    j["compared_image"] = pixels(p.compared_image);
    j["rel_error"] = numbers(p.rel_error);
  }
  return j;
}

nlohmann::json worst_json(const StressCandidate& c) {
  const WorstSample& w = c.sample;
  nlohmann::json stats = nlohmann::json::object();
  for (const auto& [k, v] : w.diagnostics.stats) stats[k] = exact_json(v);
  return {{"tier", c.tier},
          {"error", exact_json(c.error)},
          {"index", c.index},
          {"present", w.present},
          {"sample_index", w.index},
          {"sample_seed", w.sample_seed},
          {"non_finite", w.non_finite},
          {"failure", w.failure},
          {"rel_error", exact_json(w.rel_error)},
          {"ulp_error", exact_json(w.ulp_error)},
          {"abs_error", exact_json(w.abs_error)},
          {"value", rgb(w.value)},
          {"reference", rgb(w.reference)},
          {"branches", w.diagnostics.branches},
          {"stats", stats}};
}

}  // namespace

nlohmann::json exact_json(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
}

nlohmann::json to_json(const MonteCarloPart& part) {
  nlohmann::json nodes = nlohmann::json::array();
  for (const auto& [key, sums] : part.nodes)
    nodes.push_back({key.first, key.second, sums.samples(), numbers(sums.sums()), numbers(sums.sums_of_squares())});
  return {{"blocks", part.blocks},   {"scores", part.scores}, {"collisions", part.collisions},
          {"seconds", part.seconds}, {"nodes", nodes}};
}

nlohmann::json to_json(const StressPartial& partial) {
  nlohmann::json regimes = nlohmann::json::array();
  for (const auto& r : partial.regimes) {
    nlohmann::json methods = nlohmann::json::array();
    for (const auto& m : r.methods)
      methods.push_back({{"scored", m.scored},
                         {"non_finite", m.non_finite},
                         {"failures", m.failures},
                         {"underflow", m.underflow},
                         {"negative", m.negative},
                         {"max_abs_underflow", exact_json(m.max_abs_underflow)},
                         {"branches", m.branches},
                         {"worst", worst_json(m.worst)},
                         {"worst_finite", worst_json(m.worst_finite)},
                         {"rel", numbers(m.rel)},
                         {"ulp", numbers(m.ulp)}});
    regimes.push_back({{"samples", r.samples},
                       {"max_reference_rel_bound", exact_json(r.max_reference_rel_bound)},
                       {"reference_failures", r.reference_failures},
                       {"first_reference_failure", r.first_reference_failure},
                       {"reference_failure", r.reference_failure},
                       {"methods", methods}});
  }
  return {{"regimes", regimes}};
}

nlohmann::json to_json(const MeshRenderPart& p) {
  const MeshRenderCost& c = p.cost;
  nlohmann::json j = band_json(p);
  j["cost"] = {{"wall_seconds", c.wall_seconds},
               {"traversal_seconds", c.traversal_seconds},
               {"integration_seconds", c.integration_seconds},
               {"rays", c.rays},
               {"segments", c.segments},
               {"pieces", c.pieces},
               {"threads", c.threads},
               {"traversal", counters(c.traversal, kTraversalCounters)}};
  return j;
}

nlohmann::json to_json(const CellMeshRenderPart& p) {
  nlohmann::json failed = nlohmann::json::array();
  for (std::uint8_t f : p.failed) failed.push_back(f != 0 ? 1 : 0);
  nlohmann::json j = band_json(p);
  j["mode"] = "own";
  j["failed"] = failed;
  j["counts"] = {p.failed_pixels, p.rays, p.chords};
  j["max_error_estimate"] = exact_json(p.max_error_estimate);
  j["seconds"] = {exact_json(p.wall_seconds), exact_json(p.traversal_seconds), exact_json(p.integration_seconds)};
  j["threads"] = p.threads;
  j["traversal"] = counters(p.traversal, kCellTraversalCounters);
  return j;
}

nlohmann::json to_json(const SweepPart& part) {
  nlohmann::json methods = nlohmann::json::array();
  for (const auto& axis : part.methods) {
    nlohmann::json settings = nlohmann::json::array();
    for (const SweepSettingSamples& st : axis) {
      nlohmann::json cases = nlohmann::json::array();
      for (const SweepCaseSamples& c : st.cases) {
        nlohmann::json rays = nlohmann::json::array();
        for (const SweepRaySample& r : c.rays) {
          if (r.failed)
            rays.push_back({{"failure", r.failure}});
          else
            rays.push_back({r.nonfinite, exact_json(r.error[0]), exact_json(r.error[1]),
                            exact_json(r.error[2]), exact_json(r.seconds)});
        }
        nlohmann::json cj = {{"first_ray", c.first_ray},
                             {"covered", c.covered},
                             {"setup_seconds", exact_json(c.setup_seconds)},
                             {"rays", rays}};
        if (c.setup_failed) cj["setup_failure"] = c.setup_failure;
        cases.push_back(std::move(cj));
      }
      settings.push_back({{"wall_seconds", exact_json(st.wall_seconds)}, {"cases", cases}});
    }
    methods.push_back(std::move(settings));
  }
  const auto load = [](const std::array<double, 3>& l) { return nlohmann::json{exact_json(l[0]), exact_json(l[1]), exact_json(l[2])}; };
  return {{"run",
           {{"started_at", part.started_at},
            {"hardware_threads", part.hardware_threads},
            {"load_start", load(part.load_start)},
            {"load_end", load(part.load_end)},
            {"reference_seconds", exact_json(part.reference_seconds)},
            {"measure_seconds", exact_json(part.measure_seconds)}}},
          {"methods", methods}};
}

nlohmann::json to_json(const SceneRenderPart& part) {
  const std::size_t terms = part.work.empty() ? 0 : part.work.size() - 1;
  std::vector<Rgb> ray_terms, line_sums;
  for (const auto& t : part.ray_terms) ray_terms.insert(ray_terms.end(), t.begin(), t.end());
  for (const auto& t : part.line_sums) line_sums.insert(line_sums.end(), t.begin(), t.end());
  nlohmann::json work = nlohmann::json::array();
  for (const EffectWork& w : part.work)
    work.push_back({exact_json(w.seconds), exact_json(w.cpu_seconds), exact_json(w.setup_seconds),
                    exact_json(w.setup_cpu_seconds), w.rays, w.samples, w.shadow_rays, w.shadow_samples, w.lookups});
  return {{"width", part.width},
          {"height", part.height},
          {"lines", part.lines},
          {"line_begin", part.line_begin},
          {"line_end", part.line_end},
          {"terms", terms},
          {"pixels", pixels(part.pixels)},
          {"ray_terms", pixels(ray_terms)},
          {"line_sums", pixels(line_sums)},
          {"work", work},
          {"render_seconds", exact_json(part.render_seconds)},
          {"render_cpu_seconds", exact_json(part.render_cpu_seconds)},
          {"setup_seconds", exact_json(part.setup_seconds)},
          {"setup_cpu_seconds", exact_json(part.setup_cpu_seconds)},
          {"threads", part.threads}};
}

nlohmann::json to_json(const VolumeComparisonPart& part) {
  const auto estimate = [](const EstimateImage& e) {
    const PathTraceStats& t = e.stats;
    return nlohmann::json{{"mean", numbers(e.mean)},
                          {"std_error", numbers(e.std_error)},
                          {"stats", {t.paths, t.real_collisions, t.tentative_collisions, t.shadow_rays, exact_json(t.seconds)}}};
  };
  nlohmann::json runs = nlohmann::json::array();
  for (std::size_t k = 0; k < part.runs.size(); ++k) {
    const MethodRun& r = part.runs[k];
    runs.push_back({{"index", part.run_index[k]},
                    {"method", r.method},
                    {"grid", r.grid},
                    {"bins", r.bins},
                    {"iterations", r.iterations},
                    {"converged", r.converged},
                    {"setup_seconds", exact_json(r.setup_seconds)},
                    {"gather_seconds", exact_json(r.gather_seconds)},
                    {"image", numbers(r.image)}});
  }
  nlohmann::json j = rows_json(part);
  j["reference_all"] = estimate(part.reference_all);
  j["reference_single"] = estimate(part.reference_single);
  j["runs"] = runs;
  return j;
}

nlohmann::json to_json(const CellsSamples& part) {
  nlohmann::json cells = nlohmann::json::array();
  for (const auto& type : part.cells) {
    nlohmann::json samples = nlohmann::json::array();
    for (const CellRaySample& s : type)
      samples.push_back({{"level_error", numbers(s.level_error)},
                         {"level_segments", numbers(s.level_segments)},
                         {"level_decompose_s", numbers(s.level_decompose_s)},
                         {"level_exact_s", numbers(s.level_exact_s)},
                         {"ode", {exact_json(s.ode_error), exact_json(s.ode_s), exact_json(s.ode_steps)}},
                         {"reference", {exact_json(s.reference_s), exact_json(s.pieces), exact_json(s.bound_rel)}}});
    cells.push_back(std::move(samples));
  }
  nlohmann::json voxels = nlohmann::json::array();
  for (const auto& grid : part.voxels) {
    nlohmann::json samples = nlohmann::json::array();
    for (const VoxelRaySample& s : grid)
      samples.push_back({exact_json(s.error), exact_json(s.segments), exact_json(s.exact_s), exact_json(s.reference_s)});
    voxels.push_back(std::move(samples));
  }
  return {{"cells", cells}, {"voxels", voxels}, {"seconds", part.seconds}};
}

}  // namespace rayint
