// Reads shard data (shard_reader.hpp). Structure problems are InputErrors naming the field.
#include "rayint/input/shard_reader.hpp"

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
  const nlohmann::json& nodes = r.array(j, path, "nodes");
  const std::string np = field::member_path(path, "nodes");
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const std::string ip = field::index_path(np, i);
    const nlohmann::json& n = nodes[i];
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
  }
  return p;
}

StressPartial stress_partial_from_json(const nlohmann::json& j, const std::string& source,
                                       const std::string& path) {
  const Reader r{source};
  StressPartial part;
  const nlohmann::json& regimes = r.array(j, path, "regimes");
  const std::string rp = field::member_path(path, "regimes");
  for (std::size_t i = 0; i < regimes.size(); ++i) {
    const std::string ip = field::index_path(rp, i);
    const nlohmann::json& g = regimes[i];
    StressRegimePartial out;
    out.max_reference_rel_bound = r.number(g, ip, "max_reference_rel_bound");
    out.reference_failures = static_cast<long>(r.nonneg(g, ip, "reference_failures"));
    out.first_reference_failure = static_cast<long>(r.integer(g, ip, "first_reference_failure"));
    out.reference_failure = r.string(g, ip, "reference_failure");
    const nlohmann::json& methods = r.array(g, ip, "methods");
    const std::string mp = field::member_path(ip, "methods");
    for (std::size_t k = 0; k < methods.size(); ++k) {
      const std::string kp = field::index_path(mp, k);
      const nlohmann::json& m = methods[k];
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
    }
    part.regimes.push_back(std::move(out));
  }
  return part;
}

MeshRenderPart mesh_render_part_from_json(const nlohmann::json& j, const std::string& source,
                                          const std::string& path) {
  const Reader r{source};
  MeshRenderPart p;
  p.width = static_cast<int>(r.nonneg(j, path, "width"));
  p.height = static_cast<int>(r.nonneg(j, path, "height"));
  p.row_begin = static_cast<int>(r.nonneg(j, path, "row_begin"));
  p.row_end = static_cast<int>(r.nonneg(j, path, "row_end"));
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
  const nlohmann::json& t = r.array(c, cp, "traversal");
  const std::string tp = field::member_path(cp, "traversal");
  if (t.size() != 7) r.fail(tp, "must hold 7 counts");
  long* fields[] = {&cost.traversal.rays, &cost.traversal.crossings, &cost.traversal.face_steps,
                    &cost.traversal.zero_length_steps, &cost.traversal.star_searches,
                    &cost.traversal.first_hit_queries, &cost.traversal.budget_exhausted};
  for (std::size_t i = 0; i < 7; ++i) *fields[i] = static_cast<long>(r.integer(t[i], field::index_path(tp, i)));
  return p;
}

}  // namespace rayint
