// Reads shard data (shard_reader.hpp). Structure problems are InputErrors naming the field.
#include "rayint/input/shard_reader.hpp"

#include <algorithm>
#include <limits>

#include "rayint/core/error.hpp"

namespace rayint {
namespace {

struct Reader {
  const std::string& source;

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    field::fail(source, path, what);
  }
  const nlohmann::json& at(const nlohmann::json& j, const std::string& path, const char* key) const {
    if (!j.is_object()) fail(path, "must be an object");
    const auto it = j.find(key);
    if (it == j.end()) fail(field::member_path(path, key), "missing");
    return *it;
  }
  double number(const nlohmann::json& j, const std::string& path) const {
    if (j.is_number()) return j.get<double>();
    if (j == "inf") return std::numeric_limits<double>::infinity();
    if (j == "-inf") return -std::numeric_limits<double>::infinity();
    if (j == "nan") return std::numeric_limits<double>::quiet_NaN();
    fail(path, "must be a number (or \"inf\", \"-inf\", \"nan\")");
  }
  double number(const nlohmann::json& j, const std::string& path, const char* key) const {
    return number(at(j, path, key), field::member_path(path, key));
  }
  long long integer(const nlohmann::json& j, const std::string& path) const {
    if (!j.is_number_integer()) fail(path, "must be an integer");
    return j.get<long long>();
  }
  long long integer(const nlohmann::json& j, const std::string& path, const char* key) const {
    return integer(at(j, path, key), field::member_path(path, key));
  }
  long long nonneg(const nlohmann::json& j, const std::string& path, const char* key) const {
    const long long v = integer(j, path, key);
    if (v < 0) fail(field::member_path(path, key), "must be >= 0");
    return v;
  }
  bool boolean(const nlohmann::json& j, const std::string& path, const char* key) const {
    const nlohmann::json& v = at(j, path, key);
    if (!v.is_boolean()) fail(field::member_path(path, key), "must be true or false");
    return v.get<bool>();
  }
  std::string string(const nlohmann::json& j, const std::string& path, const char* key) const {
    const nlohmann::json& v = at(j, path, key);
    if (!v.is_string()) fail(field::member_path(path, key), "must be a string");
    return v.get<std::string>();
  }
  const nlohmann::json& array(const nlohmann::json& j, const std::string& path, const char* key) const {
    const nlohmann::json& v = at(j, path, key);
    if (!v.is_array()) fail(field::member_path(path, key), "must be an array");
    return v;
  }
  // Calls f(element, its path) for each element of the array `a` at `path`; `what` is the
  // refusal when `a` is not an array (e.g. "must be an array of samples").
  template <class F>
  void elements(const nlohmann::json& a, const std::string& path, const char* what, F&& f) const {
    if (!a.is_array()) fail(path, what);
    for (std::size_t i = 0; i < a.size(); ++i) f(a[i], field::index_path(path, i));
  }
  // The same for the array member `key` of `j`.
  template <class F>
  void each(const nlohmann::json& j, const std::string& path, const char* key, F&& f) const {
    elements(array(j, path, key), field::member_path(path, key), "must be an array", f);
  }
  std::vector<double> numbers(const nlohmann::json& a, const std::string& path) const {
    if (!a.is_array()) fail(path, "must be an array");
    std::vector<double> v;
    v.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) v.push_back(number(a[i], field::index_path(path, i)));
    return v;
  }
  std::vector<double> numbers(const nlohmann::json& j, const std::string& path, const char* key) const {
    return numbers(at(j, path, key), field::member_path(path, key));
  }
  Rgb rgb(const nlohmann::json& j, const std::string& path, const char* key) const {
    const std::vector<double> v = numbers(j, path, key);
    if (v.size() != 3) fail(field::member_path(path, key), "must hold 3 numbers");
    return {v[0], v[1], v[2]};
  }
  std::vector<Rgb> pixels(const nlohmann::json& j, const std::string& path, const char* key, std::size_t n) const {
    const std::vector<double> v = numbers(j, path, key);
    if (v.size() != 3 * n) fail(field::member_path(path, key), "must hold " + std::to_string(3 * n) + " numbers");
    std::vector<Rgb> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    return out;
  }
  // The array member `key` of `j` into the counters `list` of `stats` (its length, integers).
  template <class Stats, std::size_t N>
  void counters(const nlohmann::json& j, const std::string& path, const char* key, Stats& stats,
                const std::array<Counter<Stats>, N>& list) const {
    const nlohmann::json& t = array(j, path, key);
    const std::string tp = field::member_path(path, key);
    if (t.size() != N) fail(tp, "must hold " + std::to_string(N) + " counts");
    for (std::size_t i = 0; i < N; ++i) stats.*list[i].member = static_cast<long>(integer(t[i], field::index_path(tp, i)));
  }
  std::map<std::string, long> counts(const nlohmann::json& j, const std::string& path, const char* key) const {
    const nlohmann::json& v = at(j, path, key);
    const std::string p = field::member_path(path, key);
    if (!v.is_object()) fail(p, "must be an object");
    std::map<std::string, long> out;
    for (auto it = v.begin(); it != v.end(); ++it) out[it.key()] = static_cast<long>(integer(it.value(), field::member_path(p, it.key())));
    return out;
  }
  StressCandidate candidate(const nlohmann::json& j, const std::string& path) const {
    StressCandidate c;
    c.tier = static_cast<int>(integer(j, path, "tier"));
    c.error = number(j, path, "error");
    c.index = static_cast<long>(integer(j, path, "index"));
    WorstSample& w = c.sample;
    w.present = boolean(j, path, "present");
    w.index = static_cast<long>(integer(j, path, "sample_index"));
    const nlohmann::json& seed = at(j, path, "sample_seed");
    if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0))
      fail(field::member_path(path, "sample_seed"), "must be an unsigned integer");
    w.sample_seed = seed.get<std::uint64_t>();
    w.non_finite = boolean(j, path, "non_finite");
    w.failure = string(j, path, "failure");
    w.rel_error = number(j, path, "rel_error");
    w.ulp_error = number(j, path, "ulp_error");
    w.abs_error = number(j, path, "abs_error");
    w.value = rgb(j, path, "value");
    w.reference = rgb(j, path, "reference");
    w.diagnostics.branches = counts(j, path, "branches");
    const nlohmann::json& stats = at(j, path, "stats");
    if (!stats.is_object()) fail(field::member_path(path, "stats"), "must be an object");
    for (auto it = stats.begin(); it != stats.end(); ++it)
      w.diagnostics.stats[it.key()] = number(it.value(), field::member_path(field::member_path(path, "stats"), it.key()));
    return c;
  }
};

}  // namespace

MonteCarloPart monte_carlo_part_from_json(const nlohmann::json& j, const std::string& source,
                                          const std::string& path) {
  const Reader r{source};
  MonteCarloPart p;
  p.blocks = static_cast<std::size_t>(r.nonneg(j, path, "blocks"));
  p.scores = static_cast<std::size_t>(r.nonneg(j, path, "scores"));
  p.collisions = r.nonneg(j, path, "collisions");
  p.seconds = r.number(j, path, "seconds");
  r.each(j, path, "nodes", [&](const nlohmann::json& n, const std::string& ip) {
    if (!n.is_array() || n.size() != 5) r.fail(ip, "must be [level, index, samples, [sums], [sums of squares]]");
    const long long level = r.integer(n[0], field::index_path(ip, 0));
    const long long index = r.integer(n[1], field::index_path(ip, 1));
    const long long samples = r.integer(n[2], field::index_path(ip, 2));
    if (level < 0 || level > 62 || index < 0 || samples < 0) r.fail(ip, "level, index and samples must be >= 0");
    std::vector<double> sum = r.numbers(n[3], field::index_path(ip, 3));
    std::vector<double> sum2 = r.numbers(n[4], field::index_path(ip, 4));
    if (sum.size() != p.scores || sum2.size() != p.scores) r.fail(ip, "must hold `scores` sums and sums of squares");
    if (!p.nodes.emplace(BlockSumTree::Key{static_cast<int>(level), static_cast<std::size_t>(index)},
                         ScoreSums(std::move(sum), std::move(sum2), samples))
             .second)
      r.fail(ip, "duplicate node");
  });
  return p;
}

StressPartial stress_partial_from_json(const nlohmann::json& j, const std::string& source,
                                       const std::string& path) {
  const Reader r{source};
  StressPartial part;
  r.each(j, path, "regimes", [&](const nlohmann::json& g, const std::string& ip) {
    StressRegimePartial out;
    out.samples = static_cast<long>(r.nonneg(g, ip, "samples"));
    out.max_reference_rel_bound = r.number(g, ip, "max_reference_rel_bound");
    out.reference_failures = static_cast<long>(r.nonneg(g, ip, "reference_failures"));
    out.first_reference_failure = static_cast<long>(r.integer(g, ip, "first_reference_failure"));
    out.reference_failure = r.string(g, ip, "reference_failure");
    r.each(g, ip, "methods", [&](const nlohmann::json& m, const std::string& kp) {
      StressMethodPartial o;
      o.scored = static_cast<long>(r.nonneg(m, kp, "scored"));
      o.non_finite = static_cast<long>(r.nonneg(m, kp, "non_finite"));
      o.failures = static_cast<long>(r.nonneg(m, kp, "failures"));
      o.underflow = static_cast<long>(r.nonneg(m, kp, "underflow"));
      o.negative = static_cast<long>(r.nonneg(m, kp, "negative"));
      o.max_abs_underflow = r.number(m, kp, "max_abs_underflow");
      o.branches = r.counts(m, kp, "branches");
      o.worst = r.candidate(r.at(m, kp, "worst"), field::member_path(kp, "worst"));
      o.worst_finite = r.candidate(r.at(m, kp, "worst_finite"), field::member_path(kp, "worst_finite"));
      o.rel = r.numbers(m, kp, "rel");
      o.ulp = r.numbers(m, kp, "ulp");
      out.methods.push_back(std::move(o));
    });
    part.regimes.push_back(std::move(out));
  });
  return part;
}

namespace {

// The rows [row_begin, row_end) of a width x height image a part holds (report/shard_json.cpp
// rows_json): four integers >= 0, which the caller checks against its own limits.
template <class Part>
void read_rows(const Reader& r, const nlohmann::json& j, const std::string& path, Part& p) {
  p.width = static_cast<int>(r.nonneg(j, path, "width"));
  p.height = static_cast<int>(r.nonneg(j, path, "height"));
  p.row_begin = static_cast<int>(r.nonneg(j, path, "row_begin"));
  p.row_end = static_cast<int>(r.nonneg(j, path, "row_end"));
}

// The band both mesh renders' shard parts share: its rows (checked), the image and, when
// compared, the compared image and per-pixel errors. Returns the band's pixel count.
template <class Part>
std::size_t read_band(const Reader& r, const nlohmann::json& j, const std::string& path, Part& p) {
  read_rows(r, j, path, p);
  if (p.width > 65536 || p.height > 65536 || static_cast<long long>(p.width) * p.height > (1LL << 26) ||
      p.row_end > p.height || p.row_begin > p.row_end)
    r.fail(path, "needs width, height <= 65536, at most 2^26 pixels and 0 <= row_begin <= row_end <= height");
  p.compared = r.boolean(j, path, "compared");
  const std::size_t n = static_cast<std::size_t>(p.row_end - p.row_begin) * static_cast<std::size_t>(p.width);
  p.image = r.pixels(j, path, "image", n);
  if (p.compared) {
    p.compared_image = r.pixels(j, path, "compared_image", n);
    p.rel_error = r.numbers(j, path, "rel_error");
    if (p.rel_error.size() != n) r.fail(field::member_path(path, "rel_error"), "must hold one number per pixel");
  }
  return n;
}

}  // namespace

MeshRenderPart mesh_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                          const std::string& path) {
  const Reader r{source};
  MeshRenderPart p;
  read_band(r, j, path, p);
  const nlohmann::json& c = r.at(j, path, "cost");
  const std::string cp = field::member_path(path, "cost");
  MeshRenderCost& cost = p.cost;
  cost.wall_seconds = r.number(c, cp, "wall_seconds");
  cost.traversal_seconds = r.number(c, cp, "traversal_seconds");
  cost.integration_seconds = r.number(c, cp, "integration_seconds");
  cost.rays = static_cast<long>(r.nonneg(c, cp, "rays"));
  cost.segments = static_cast<long>(r.nonneg(c, cp, "segments"));
  cost.pieces = static_cast<long>(r.nonneg(c, cp, "pieces"));
  cost.threads = static_cast<unsigned>(r.nonneg(c, cp, "threads"));
  r.counters(c, cp, "traversal", cost.traversal, kTraversalCounters);
  return p;
}

CellMeshRenderPart cell_mesh_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                                   const std::string& path) {
  const Reader r{source};
  if (!(r.at(j, path, "mode") == "own")) r.fail(field::member_path(path, "mode"), "must be \"own\" (an own-mode render's band)");
  CellMeshRenderPart p;
  const std::size_t n = read_band(r, j, path, p);
  const nlohmann::json& failed = r.array(j, path, "failed");
  const std::string fp = field::member_path(path, "failed");
  if (failed.size() != n) r.fail(fp, "must hold one 0 or 1 per pixel");
  for (std::size_t i = 0; i < n; ++i) {
    const long long f = r.integer(failed[i], field::index_path(fp, i));
    if (f != 0 && f != 1) r.fail(field::index_path(fp, i), "must be 0 or 1");
    p.failed.push_back(static_cast<std::uint8_t>(f));
  }
  const nlohmann::json& counts = r.array(j, path, "counts");
  const std::string cp = field::member_path(path, "counts");
  if (counts.size() != 3) r.fail(cp, "must hold 3 counts (failed pixels, rays, chords)");
  long* cf[] = {&p.failed_pixels, &p.rays, &p.chords};
  for (std::size_t i = 0; i < 3; ++i) {
    const long long v = r.integer(counts[i], field::index_path(cp, i));
    if (v < 0) r.fail(field::index_path(cp, i), "must be >= 0");
    *cf[i] = static_cast<long>(v);
  }
  p.max_error_estimate = r.number(j, path, "max_error_estimate");
  const std::vector<double> sec = r.numbers(j, path, "seconds");
  if (sec.size() != 3) r.fail(field::member_path(path, "seconds"), "must hold 3 numbers (wall, traversal, integration)");
  p.wall_seconds = sec[0];
  p.traversal_seconds = sec[1];
  p.integration_seconds = sec[2];
  p.threads = static_cast<unsigned>(r.nonneg(j, path, "threads"));
  r.counters(j, path, "traversal", p.traversal, kCellTraversalCounters);
  return p;
}

SceneRenderPart scene_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                            const std::string& path) {
  const Reader r{source};
  SceneRenderPart p;
  p.width = static_cast<int>(r.nonneg(j, path, "width"));
  p.height = static_cast<int>(r.nonneg(j, path, "height"));
  p.lines = r.nonneg(j, path, "lines");
  p.line_begin = r.nonneg(j, path, "line_begin");
  p.line_end = r.nonneg(j, path, "line_end");
  const long long terms = r.nonneg(j, path, "terms");
  const long long pixels = static_cast<long long>(p.width) * p.height;
  if (p.width > (1 << 26) || p.height > 65536 || pixels > (1LL << 26) || terms > 64 ||
      (p.lines != p.height && p.lines != pixels) || p.line_end > p.lines || p.line_begin > p.line_end)
    r.fail(path, "needs at most 2^26 pixels, 64 terms, lines = height (rows) or width (rays) and "
                 "0 <= line_begin <= line_end <= lines");
  const std::size_t n_lines = static_cast<std::size_t>(p.line_end - p.line_begin);
  // A line is a row (lines = height) or an explicit ray (lines = width, height 1).
  const std::size_t per_line = p.lines == p.height ? static_cast<std::size_t>(p.width) : 1;
  const std::size_t n = n_lines * per_line;
  const auto nt = static_cast<std::size_t>(terms);
  p.pixels = r.pixels(j, path, "pixels", n);
  const nlohmann::json& rt = r.array(j, path, "ray_terms");
  if (!rt.empty()) {
    const std::vector<Rgb> flat = r.pixels(j, path, "ray_terms", n * nt);
    for (std::size_t i = 0; i < n; ++i) p.ray_terms.emplace_back(flat.begin() + static_cast<long>(i * nt),
                                                                 flat.begin() + static_cast<long>((i + 1) * nt));
  }
  const std::vector<Rgb> sums = r.pixels(j, path, "line_sums", n_lines * (nt + 1));
  for (std::size_t i = 0; i < n_lines; ++i)
    p.line_sums.emplace_back(sums.begin() + static_cast<long>(i * (nt + 1)),
                             sums.begin() + static_cast<long>((i + 1) * (nt + 1)));
  const nlohmann::json& w = r.array(j, path, "work");
  const std::string wp = field::member_path(path, "work");
  if (w.size() != nt + 1) r.fail(wp, "must hold terms + 1 entries");
  for (std::size_t e = 0; e < w.size(); ++e) {
    const std::string ep = field::index_path(wp, e);
    if (!w[e].is_array() || w[e].size() != 9) r.fail(ep, "must hold 4 times and 5 counts");
    EffectWork ew;
    double* times[] = {&ew.seconds, &ew.cpu_seconds, &ew.setup_seconds, &ew.setup_cpu_seconds};
    for (std::size_t k = 0; k < 4; ++k) *times[k] = r.number(w[e][k], field::index_path(ep, k));
    long long* counts[] = {&ew.rays, &ew.samples, &ew.shadow_rays, &ew.shadow_samples, &ew.lookups};
    for (std::size_t k = 0; k < 5; ++k) *counts[k] = r.integer(w[e][4 + k], field::index_path(ep, 4 + k));
    p.work.push_back(ew);
  }
  p.render_seconds = r.number(j, path, "render_seconds");
  p.render_cpu_seconds = r.number(j, path, "render_cpu_seconds");
  p.setup_seconds = r.number(j, path, "setup_seconds");
  p.setup_cpu_seconds = r.number(j, path, "setup_cpu_seconds");
  p.threads = static_cast<unsigned>(r.nonneg(j, path, "threads"));
  return p;
}

SweepPart sweep_part_from_json(const nlohmann::json& j, const std::string& source,
                               const std::string& path) {
  const Reader r{source};
  SweepPart part;
  const nlohmann::json& run = r.at(j, path, "run");
  const std::string rp = field::member_path(path, "run");
  part.started_at = r.string(run, rp, "started_at");
  part.hardware_threads = static_cast<unsigned>(std::min<long long>(r.nonneg(run, rp, "hardware_threads"), 1 << 20));
  for (const char* key : {"load_start", "load_end"}) {
    const std::vector<double> v = r.numbers(run, rp, key);
    if (v.size() != 3) r.fail(field::member_path(rp, key), "must hold 3 numbers");
    (std::string(key) == "load_start" ? part.load_start : part.load_end) = {v[0], v[1], v[2]};
  }
  part.reference_seconds = r.number(run, rp, "reference_seconds");
  part.measure_seconds = r.number(run, rp, "measure_seconds");
  r.each(j, path, "methods", [&](const nlohmann::json& method, const std::string& ap) {
    std::vector<SweepSettingSamples> settings;
    r.elements(method, ap, "must be an array of settings", [&](const nlohmann::json& st, const std::string& kp) {
      SweepSettingSamples out;
      out.wall_seconds = r.number(st, kp, "wall_seconds");
      r.each(st, kp, "cases", [&](const nlohmann::json& c, const std::string& ip) {
        SweepCaseSamples cs;
        cs.first_ray = static_cast<std::size_t>(r.nonneg(c, ip, "first_ray"));
        cs.covered = static_cast<std::size_t>(r.nonneg(c, ip, "covered"));
        cs.setup_seconds = r.number(c, ip, "setup_seconds");
        if (c.contains("setup_failure")) {
          cs.setup_failed = true;
          cs.setup_failure = r.string(c, ip, "setup_failure");
        }
        r.each(c, ip, "rays", [&](const nlohmann::json& ray, const std::string& rp2) {
          SweepRaySample s;
          if (ray.is_object()) {
            s.failed = true;
            s.failure = r.string(ray, rp2, "failure");
          } else {
            const std::vector<double> v = r.numbers(ray, rp2);
            if (v.size() != 5) r.fail(rp2, "must be [nonfinite bits, error r, g, b, seconds] or {\"failure\": message}");
            const long long bits = r.integer(ray[0], field::index_path(rp2, 0));
            if (bits < 0 || bits > 7) r.fail(field::index_path(rp2, 0), "must be in [0, 7]");
            s.nonfinite = static_cast<unsigned>(bits);
            s.error = {v[1], v[2], v[3]};
            s.seconds = v[4];
          }
          cs.rays.push_back(std::move(s));
        });
        if (!cs.setup_failed && cs.rays.size() != cs.covered) r.fail(ip, "must hold `covered` rays");
        out.cases.push_back(std::move(cs));
      });
      settings.push_back(std::move(out));
    });
    part.methods.push_back(std::move(settings));
  });
  return part;
}

VolumeComparisonPart volume_comparison_part_from_json(const nlohmann::json& j, const std::string& source,
                                                      const std::string& path) {
  const Reader r{source};
  VolumeComparisonPart p;
  read_rows(r, j, path, p);
  if (p.width < 1 || p.height < 1 || p.width > 4096 || p.height > 4096 || p.row_end > p.height ||
      p.row_begin > p.row_end)
    r.fail(path, "needs 1 <= width, height <= 4096 and 0 <= row_begin <= row_end <= height");
  const std::size_t w = static_cast<std::size_t>(p.width);
  const std::size_t rows = static_cast<std::size_t>(p.row_end - p.row_begin);
  for (const char* key : {"reference_all", "reference_single"}) {
    const std::string ep = field::member_path(path, key);
    const nlohmann::json& e = r.at(j, path, key);
    EstimateImage& img = std::string(key) == "reference_all" ? p.reference_all : p.reference_single;
    img.width = p.width;
    img.height = p.row_end - p.row_begin;
    img.mean = r.numbers(e, ep, "mean");
    img.std_error = r.numbers(e, ep, "std_error");
    if (img.mean.size() != rows * w || img.std_error.size() != rows * w)
      r.fail(ep, "mean and std_error must hold one number per pixel of rows [row_begin, row_end)");
    const nlohmann::json& st = r.at(e, ep, "stats");
    const std::string sp = field::member_path(ep, "stats");
    if (!st.is_array() || st.size() != 5) r.fail(sp, "must be [paths, real collisions, tentative collisions, shadow rays, seconds]");
    long long* counts[] = {&img.stats.paths, &img.stats.real_collisions, &img.stats.tentative_collisions,
                           &img.stats.shadow_rays};
    for (std::size_t i = 0; i < 4; ++i) {
      *counts[i] = r.integer(st[i], field::index_path(sp, i));
      if (*counts[i] < 0) r.fail(field::index_path(sp, i), "must be >= 0");
    }
    img.stats.seconds = r.number(st[4], field::index_path(sp, 4));
  }
  r.each(j, path, "runs", [&](const nlohmann::json& m, const std::string& kp) {
    p.run_index.push_back(static_cast<std::size_t>(r.nonneg(m, kp, "index")));
    MethodRun run;
    run.method = r.string(m, kp, "method");
    run.grid = static_cast<int>(std::min<long long>(r.nonneg(m, kp, "grid"), 1 << 20));
    run.bins = static_cast<int>(std::min<long long>(r.nonneg(m, kp, "bins"), 1 << 20));
    run.iterations = static_cast<int>(std::min<long long>(r.nonneg(m, kp, "iterations"), 1 << 30));
    run.converged = r.boolean(m, kp, "converged");
    run.setup_seconds = r.number(m, kp, "setup_seconds");
    run.gather_seconds = r.number(m, kp, "gather_seconds");
    run.image = r.numbers(m, kp, "image");
    if (run.image.size() != w * static_cast<std::size_t>(p.height))
      r.fail(field::member_path(kp, "image"), "must hold one number per pixel");
    p.runs.push_back(std::move(run));
  });
  return p;
}

CellsSamples cells_samples_from_json(const nlohmann::json& j, const std::string& source,
                                     const std::string& path) {
  const Reader r{source};
  CellsSamples part;
  // A fixed-size array of numbers at j[i] (e.g. [error, seconds, steps]).
  const auto fixed = [&](const nlohmann::json& a, const std::string& p, std::size_t n) {
    const std::vector<double> v = r.numbers(a, p);
    if (v.size() != n) r.fail(p, "must hold " + std::to_string(n) + " numbers");
    return v;
  };
  r.each(j, path, "cells", [&](const nlohmann::json& cell, const std::string& tp) {
    std::vector<CellRaySample> samples;
    r.elements(cell, tp, "must be an array of samples", [&](const nlohmann::json& e, const std::string& ip) {
      CellRaySample s;
      s.level_error = r.numbers(e, ip, "level_error");
      s.level_segments = r.numbers(e, ip, "level_segments");
      s.level_decompose_s = r.numbers(e, ip, "level_decompose_s");
      s.level_exact_s = r.numbers(e, ip, "level_exact_s");
      const std::size_t levels = s.level_error.size();
      if (s.level_segments.size() != levels || s.level_decompose_s.size() != levels ||
          s.level_exact_s.size() != levels)
        r.fail(ip, "level_error, level_segments, level_decompose_s, level_exact_s must be equally long");
      const std::vector<double> ode = fixed(r.at(e, ip, "ode"), field::member_path(ip, "ode"), 3);
      const std::vector<double> ref = fixed(r.at(e, ip, "reference"), field::member_path(ip, "reference"), 3);
      s.ode_error = ode[0];
      s.ode_s = ode[1];
      s.ode_steps = ode[2];
      s.reference_s = ref[0];
      s.pieces = ref[1];
      s.bound_rel = ref[2];
      samples.push_back(std::move(s));
    });
    part.cells.push_back(std::move(samples));
  });
  r.each(j, path, "voxels", [&](const nlohmann::json& grid, const std::string& gp) {
    std::vector<VoxelRaySample> samples;
    r.elements(grid, gp, "must be an array of samples", [&](const nlohmann::json& e, const std::string& ip) {
      const std::vector<double> v = fixed(e, ip, 4);
      samples.push_back({v[0], v[1], v[2], v[3]});
    });
    part.voxels.push_back(std::move(samples));
  });
  part.seconds = r.number(j, path, "seconds");
  return part;
}

}  // namespace rayint
