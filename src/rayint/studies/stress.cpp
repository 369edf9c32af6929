// stress.cpp -- the `rayint stress` engine (see stress.hpp for what is scored and why the result
// does not depend on thread scheduling).
//
// Plan: every regime gets an equal share of the piece budget; a piece-level regime draws that
// many samples, a ray-level one draws rays (here, once, only to count their pieces) until their
// pieces reach the share. Work: a flat list of (regime, index) items, most expensive first (the
// long rays), handed out by parallel_for (core/parallel.hpp). Each item regenerates its sample
// from its own seed, computes the reference once and runs every method on it. Per-sample errors
// go to pre-sized slots; counts, maxima and branch histograms go to per-worker accumulators that
// are merged after the run (integer sums and maxima are order independent); the worst sample is
// a maximum under a total order (severity, then lower index), so merging is order independent
// too.
#include "rayint/studies/stress.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char ch : s) {
    h ^= static_cast<unsigned char>(ch);
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string format_g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// File- and case-name friendly form of a method label ("riemann:n=64" -> "riemann-n-64").
std::string slug(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                    ch == '_' || ch == '.';
    out += ok ? ch : '-';
  }
  return out;
}

using Severity = StressCandidate;  // its tier, error and index order the samples
using MethodAccumulator = StressMethodPartial;
using RegimeAccumulator = StressRegimePartial;

struct RegimePlan {
  Regime regime;
  long samples = 0;
  long pieces = 0;
  std::vector<long> sample_pieces;  // ray-level regimes: pieces of each sample
};

struct WorkItem {
  std::size_t regime;  // index into the plan
  long index;
  long pieces;
};

// One method on one sample: integrate and score every channel.
void run_method(const MethodSpec& spec, const RaySample& sample,
                const std::array<ExtendedValue, kChannels>& ref, long index,
                std::uint64_t seed_of_sample, MethodAccumulator& acc, double& rel_slot,
                double& ulp_slot) {
  Diagnostics diag;
  RayResult result;
  std::string failure;
  try {
    const std::unique_ptr<RayIntegrator> integrator = make_integrator(spec, sample.transfer);
    result = integrator->integrate(sample.ray, &diag);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  const SampleScore score = score_sample(result, ref, !failure.empty());
  const bool finite = score.finite;
  const double rel = score.rel, ulp = score.ulp;
  const double abs_scored = score.abs_scored, abs_underflow = score.abs_underflow;
  const bool any_scored = score.scored, any_underflow = score.underflow;
  for (const auto& [branch, n] : diag.branches) acc.branches[branch] += n;

  Severity sev;
  sev.index = index;
  if (!finite) {
    ++acc.non_finite;
    if (!failure.empty()) ++acc.failures;
    sev.tier = 2;
    sev.error = 0.0;
  } else {
    for (int c = 0; c < kChannels; ++c)
      if (result.intensity[c] < 0.0 || result.transmittance[c] < 0.0) {
        ++acc.negative;
        break;
      }
    if (any_scored) {
      ++acc.scored;
      rel_slot = rel;
      ulp_slot = ulp;
      sev.tier = 1;
      sev.error = rel;
    } else {
      sev.tier = 0;
      sev.error = abs_underflow;
    }
    if (any_underflow) {
      ++acc.underflow;
      acc.max_abs_underflow = std::max(acc.max_abs_underflow, abs_underflow);
    }
  }
  auto keep = [&](StressCandidate& into) {
    if (!sev.worse_than(into)) return;
    WorstSample& w = into.sample;
    into.tier = sev.tier;
    into.error = sev.error;
    into.index = sev.index;
    w.present = true;
    w.index = index;
    w.sample_seed = seed_of_sample;
    w.non_finite = !finite;
    w.failure = failure;
    w.rel_error = finite ? rel : std::numeric_limits<double>::infinity();
    w.ulp_error = finite ? ulp : std::numeric_limits<double>::infinity();
    w.abs_error = finite ? std::max(abs_scored, abs_underflow) : std::numeric_limits<double>::infinity();
    w.value = result.intensity;
    for (int c = 0; c < kChannels; ++c) w.reference[c] = ref[c].hi;
    w.diagnostics = diag;
  };
  keep(acc.worst);
  if (finite) keep(acc.worst_finite);
}

// The counts, the largest underflow error and the branch counts (not the worst samples).
void add_counts(MethodAccumulator& into, const MethodAccumulator& from) {
  into.scored += from.scored;
  into.non_finite += from.non_finite;
  into.failures += from.failures;
  into.negative += from.negative;
  into.underflow += from.underflow;
  into.max_abs_underflow = std::max(into.max_abs_underflow, from.max_abs_underflow);
  for (const auto& [k, v] : from.branches) into.branches[k] += v;
}

void merge_into(MethodAccumulator& into, const MethodAccumulator& from) {
  add_counts(into, from);
  if (from.worst.worse_than(into.worst)) into.worst = from.worst;
  if (from.worst_finite.worse_than(into.worst_finite)) into.worst_finite = from.worst_finite;
}

void merge_regime(RegimeAccumulator& into, const RegimeAccumulator& from) {
  into.samples += from.samples;
  into.max_reference_rel_bound = std::max(into.max_reference_rel_bound, from.max_reference_rel_bound);
  into.reference_failures += from.reference_failures;
  if (from.first_reference_failure >= 0 &&
      (into.first_reference_failure < 0 || from.first_reference_failure < into.first_reference_failure)) {
    into.first_reference_failure = from.first_reference_failure;
    into.reference_failure = from.reference_failure;
  }
  if (into.methods.size() < from.methods.size()) into.methods.resize(from.methods.size());
  for (std::size_t m = 0; m < from.methods.size(); ++m) {
    merge_into(into.methods[m], from.methods[m]);
    into.methods[m].rel.insert(into.methods[m].rel.end(), from.methods[m].rel.begin(), from.methods[m].rel.end());
    into.methods[m].ulp.insert(into.methods[m].ulp.end(), from.methods[m].ulp.begin(), from.methods[m].ulp.end());
  }
}

std::vector<RegimePlan> plan(const StressOptions& opt, const std::vector<Regime>& regimes) {
  std::vector<RegimePlan> out;
  const long n = static_cast<long>(regimes.size());
  for (long r = 0; r < n; ++r) {
    RegimePlan p;
    p.regime = regimes[static_cast<std::size_t>(r)];
    const long budget = std::max(1L, opt.count / n + (r < opt.count % n ? 1 : 0));
    if (!is_ray_regime(p.regime)) {
      p.samples = p.pieces = budget;
    } else {
      while (p.pieces < budget) {
        const RaySample s = stress_sample(opt.seed, p.regime, p.samples);
        const long pieces = static_cast<long>(split_ray(s.transfer, s.ray).size());
        p.sample_pieces.push_back(pieces);
        p.pieces += std::max(1L, pieces);
        ++p.samples;
      }
    }
    out.push_back(std::move(p));
  }
  return out;
}

std::string replay_description(const std::string& regime, const std::string& method,
                               std::uint64_t seed, const WorstSample& w) {
  std::string d = "Worst sample of `rayint stress` for method " + method + " in regime " + regime +
                  ": run seed " + std::to_string(seed) + ", sample " + std::to_string(w.index) +
                  " (sample seed " + std::to_string(w.sample_seed) + "); ";
  if (w.non_finite)
    d += w.failure.empty() ? "non-finite result" : "the method failed: " + w.failure;
  else
    d += "relative error " + format_g(w.rel_error) + " (" + format_g(w.ulp_error) +
         " ulp), absolute " + format_g(w.abs_error) + ", against the 50-digit reference";
  std::string branches;
  for (const auto& [k, v] : w.diagnostics.branches)
    branches += (branches.empty() ? "" : ", ") + k + " " + std::to_string(v);
  if (!branches.empty()) d += "; branches: " + branches;
  return d + ".";
}

MethodStress to_method_stress(const std::string& label, MethodAccumulator& acc,
                              std::vector<double>& rel, std::vector<double>& ulp) {
  MethodStress m;
  m.method = label;
  m.scored = acc.scored;
  m.non_finite = acc.non_finite;
  m.failures = acc.failures;
  m.negative = acc.negative;
  m.underflow = acc.underflow;
  m.max_abs_error_underflow = acc.max_abs_underflow;
  m.branches = acc.branches;
  auto keep = [](std::vector<double>& v) {
    v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  };
  keep(rel);
  keep(ulp);
  m.rel = error_stats(rel);
  m.ulp = error_stats(ulp);
  m.worst = std::move(acc.worst.sample);
  if (m.worst.non_finite) m.worst_finite = std::move(acc.worst_finite.sample);
  return m;
}

}  // namespace

ValueScore score_value(double x, const ExtendedValue& ref) {
  ValueScore s;
  s.finite = std::isfinite(x);
  s.underflow = underflowed(ref);
  s.abs = absolute_error(x, ref);
  if (!s.underflow) {
    s.rel = scored_error(x, ref);  // the relative error, above the floor
    s.ulp = ulp_error(x, ref);
  }
  return s;
}

SampleScore score_sample(const RayResult& result, const std::array<ExtendedValue, kChannels>& ref,
                         bool failed) {
  SampleScore out;
  out.finite = !failed;
  for (int c = 0; c < kChannels && out.finite; ++c)
    out.finite = std::isfinite(result.intensity[c]) && std::isfinite(result.transmittance[c]);
  if (!out.finite) return out;
  for (int c = 0; c < kChannels; ++c) {
    const ValueScore s = score_value(result.intensity[c], ref[c]);
    if (s.underflow) {
      out.underflow = true;
      out.abs_underflow = std::max(out.abs_underflow, s.abs);
    } else {
      out.scored = true;
      out.rel = std::max(out.rel, s.rel);
      out.ulp = std::max(out.ulp, s.ulp);
      out.abs_scored = std::max(out.abs_scored, s.abs);
    }
  }
  return out;
}

std::uint64_t sample_seed(std::uint64_t seed, Regime regime, long index) {
  return splitmix64(splitmix64(splitmix64(seed) ^ fnv1a(regime_name(regime))) +
                    static_cast<std::uint64_t>(index));
}

RaySample stress_sample(std::uint64_t seed, Regime regime, long index) {
  std::mt19937_64 rng(sample_seed(seed, regime, index));
  return sample_ray(regime, rng);
}

bool StressCandidate::worse_than(const StressCandidate& o) const {
  if (tier != o.tier) return tier > o.tier;
  if (error != o.error) return error > o.error;
  return index >= 0 && (o.index < 0 || index < o.index);
}

namespace {

std::vector<MethodSpec> methods_of(const StressOptions& opt) {
  return opt.methods.empty() ? std::vector<MethodSpec>{parse_method_spec("exact")} : opt.methods;
}

}  // namespace

namespace {

// Every sample of the run in work order: the ray samples first, largest first (they bound the
// run time); then the piece samples interleaved across regimes so the progress rate is
// representative from the start. Shard I of N takes the items k with k mod N == I.
std::vector<WorkItem> work_items(const std::vector<RegimePlan>& plans) {
  std::vector<WorkItem> all_items;
  for (std::size_t r = 0; r < plans.size(); ++r) {
    if (!is_ray_regime(plans[r].regime)) continue;
    for (long i = 0; i < plans[r].samples; ++i)
      all_items.push_back({r, i, plans[r].sample_pieces[static_cast<std::size_t>(i)]});
  }
  std::stable_sort(all_items.begin(), all_items.end(),
                   [](const WorkItem& a, const WorkItem& b) { return a.pieces > b.pieces; });
  long max_piece_samples = 0;
  for (const auto& p : plans)
    if (!is_ray_regime(p.regime)) max_piece_samples = std::max(max_piece_samples, p.samples);
  for (long i = 0; i < max_piece_samples; ++i)
    for (std::size_t r = 0; r < plans.size(); ++r)
      if (!is_ray_regime(plans[r].regime) && i < plans[r].samples) all_items.push_back({r, i, 1});
  return all_items;
}

}  // namespace

std::vector<long> stress_shard_samples(const StressOptions& opt, const ShardSpec& shard) {
  const std::vector<Regime> regimes = opt.regimes.empty() ? stress_regimes() : opt.regimes;
  const std::vector<RegimePlan> plans = plan(opt, regimes);
  const std::vector<WorkItem> all_items = work_items(plans);
  std::vector<long> out(plans.size(), 0);
  for (std::size_t k = 0; k < all_items.size(); ++k)
    if (static_cast<long>(k % static_cast<std::size_t>(shard.count)) == shard.index) ++out[all_items[k].regime];
  return out;
}

StressPartial run_stress_part(const StressOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const std::vector<Regime> regimes = opt.regimes.empty() ? stress_regimes() : opt.regimes;
  const std::vector<MethodSpec> methods = methods_of(opt);
  if (opt.count < 1) throw std::invalid_argument("stress: count must be >= 1");
  {  // fail now, not once per sample, for a method that cannot be built at all
    const RaySample probe = stress_sample(opt.seed, Regime::moderate, 0);
    for (const auto& spec : methods) make_integrator(spec, probe.transfer);
  }

  const std::vector<RegimePlan> plans = plan(opt, regimes);
  const std::size_t n_methods = methods.size();
  const std::vector<WorkItem> all_items = work_items(plans);
  // This shard's items: k mod N == I (round-robin over the cost-sorted list).
  std::vector<WorkItem> items;
  long total_pieces = 0;
  for (std::size_t k = 0; k < all_items.size(); ++k)
    if (static_cast<long>(k % static_cast<std::size_t>(opt.shard.count)) == opt.shard.index) {
      items.push_back(all_items[k]);
      total_pieces += all_items[k].pieces;
    }

  // Slots: rel[r][m][i], ulp[r][m][i]; NaN = not scored (or not in this shard).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::vector<std::vector<double>>> rel(plans.size()), ulp(plans.size());
  for (std::size_t r = 0; r < plans.size(); ++r) {
    rel[r].assign(n_methods, std::vector<double>(static_cast<std::size_t>(plans[r].samples), nan));
    ulp[r] = rel[r];
  }

  const unsigned n_workers = parallel_workers(static_cast<long long>(items.size()), opt.threads);
  std::vector<std::vector<RegimeAccumulator>> acc(n_workers);
  for (auto& per_worker : acc) {
    per_worker.resize(plans.size());
    for (auto& ra : per_worker) ra.methods.resize(n_methods);
  }

  std::atomic<long> samples_done{0}, pieces_done{0};
  auto run_item = [&](long long k, unsigned w) {
    const WorkItem& item = items[static_cast<std::size_t>(k)];
    const Regime regime = plans[item.regime].regime;
    RegimeAccumulator& ra = acc[w][item.regime];
    const std::uint64_t s_seed = sample_seed(opt.seed, regime, item.index);
    std::mt19937_64 rng(s_seed);
    RaySample sample;
    std::array<ExtendedValue, kChannels> ref{};
    Rgb bound{};
    try {
      if (is_ray_regime(regime)) {
        sample = sample_ray(regime, rng);
        const ReferenceRay rr = reference_ray(sample.transfer, sample.ray);
        ref = rr.intensity;
        bound = rr.error_bound;
      } else {
        const RegimeSample ps = sample_piece(regime, rng);
        sample = piece_as_ray(ps);
        const ReferencePiece rp = reference_piece(ps.piece, ps.incoming);
        ref = {rp.intensity, rp.intensity, rp.intensity};
        bound = {rp.error_bound, rp.error_bound, rp.error_bound};
      }
    } catch (const std::exception& e) {
      ++ra.reference_failures;
      if (ra.first_reference_failure < 0 || item.index < ra.first_reference_failure) {
        ra.first_reference_failure = item.index;
        ra.reference_failure = "sample " + std::to_string(item.index) + ": " + e.what();
      }
      ++ra.samples;
      ++samples_done;
      pieces_done += item.pieces;
      return;
    }
    for (int c = 0; c < kChannels; ++c)
      if (!underflowed(ref[c]))
        ra.max_reference_rel_bound = std::max(ra.max_reference_rel_bound, bound[c] / std::fabs(ref[c].hi));
    const auto idx = static_cast<std::size_t>(item.index);
    for (std::size_t m = 0; m < n_methods; ++m)
      run_method(methods[m], sample, ref, item.index, s_seed, ra.methods[m],
                 rel[item.regime][m][idx], ulp[item.regime][m][idx]);
    ++ra.samples;
    ++samples_done;
    pieces_done += item.pieces;
  };

  const long total_samples = static_cast<long>(items.size());
  auto report_progress = [&] {
    if (!opt.progress) return;
    StressProgress p;
    p.samples_done = samples_done;
    p.samples_total = total_samples;
    p.pieces_done = pieces_done;
    p.pieces_total = total_pieces;
    p.seconds = std::chrono::duration<double>(clock::now() - start).count();
    opt.progress(p);
  };

  parallel_for(static_cast<long long>(items.size()), opt.threads, run_item,
               std::max(0.05, opt.progress_interval_seconds), report_progress);
  report_progress();

  // Merge the per-worker accumulators (worker 0 collects); the scored slots become value lists.
  StressPartial part;
  for (std::size_t r = 0; r < plans.size(); ++r) {
    RegimeAccumulator& into = acc[0][r];
    for (unsigned t = 1; t < n_workers; ++t) merge_regime(into, acc[t][r]);
    for (std::size_t m = 0; m < n_methods; ++m) {
      for (const double x : rel[r][m])
        if (!std::isnan(x)) into.methods[m].rel.push_back(x);
      for (const double x : ulp[r][m])
        if (!std::isnan(x)) into.methods[m].ulp.push_back(x);
    }
    part.regimes.push_back(std::move(into));
  }
  return part;
}

StressReport finish_stress(const StressOptions& opt, const std::vector<StressPartial>& parts) {
  const std::vector<Regime> regimes = opt.regimes.empty() ? stress_regimes() : opt.regimes;
  const std::vector<MethodSpec> methods = methods_of(opt);
  const std::vector<RegimePlan> plans = plan(opt, regimes);
  const std::size_t n_methods = methods.size();
  for (const auto& part : parts) {
    if (part.regimes.size() != plans.size())
      throw std::invalid_argument("stress: a part has " + std::to_string(part.regimes.size()) +
                                  " regimes, the run " + std::to_string(plans.size()));
    for (const auto& ra : part.regimes)
      if (ra.methods.size() != n_methods)
        throw std::invalid_argument("stress: a part has " + std::to_string(ra.methods.size()) +
                                    " methods, the run " + std::to_string(n_methods));
  }

  StressReport report;
  report.seed = opt.seed;
  report.count = opt.count;
  for (const auto& spec : methods) report.methods.push_back(spec.label());
  std::vector<MethodAccumulator> pooled_acc(n_methods);
  std::vector<std::vector<double>> pooled_rel(n_methods), pooled_ulp(n_methods);
  for (std::size_t r = 0; r < plans.size(); ++r) {
    RegimeAccumulator into;
    into.methods.resize(n_methods);
    for (const auto& part : parts) merge_regime(into, part.regimes[r]);
    RegimeStress rs;
    rs.regime = regime_name(plans[r].regime);
    rs.ray_level = is_ray_regime(plans[r].regime);
    rs.samples = plans[r].samples;
    rs.pieces = plans[r].pieces;
    rs.max_reference_rel_bound = into.max_reference_rel_bound;
    rs.reference_failures = into.reference_failures;
    rs.reference_failure = into.reference_failure;
    for (std::size_t m = 0; m < n_methods; ++m) {
      MethodAccumulator& ma = into.methods[m];
      // pooled figures first (to_method_stress consumes the value lists)
      add_counts(pooled_acc[m], ma);
      pooled_rel[m].insert(pooled_rel[m].end(), ma.rel.begin(), ma.rel.end());
      pooled_ulp[m].insert(pooled_ulp[m].end(), ma.ulp.begin(), ma.ulp.end());

      MethodStress ms = to_method_stress(report.methods[m], ma, ma.rel, ma.ulp);
      auto replay = [&](WorstSample& w, const std::string& suffix) {
        if (!w.present) return;
        const RaySample s = stress_sample(opt.seed, plans[r].regime, w.index);
        Case& c = w.replay;
        c.name = "stress-" + rs.regime + "-" + slug(ms.method) + suffix;
        c.description = replay_description(rs.regime, ms.method, opt.seed, w);
        c.transfer = s.transfer;
        c.rays = {s.ray};
      };
      replay(ms.worst, "");
      replay(ms.worst_finite, "-finite");
      rs.methods.push_back(std::move(ms));
    }
    report.regimes.push_back(std::move(rs));
  }
  for (std::size_t m = 0; m < n_methods; ++m) {
    report.overall.push_back(
        to_method_stress(report.methods[m], pooled_acc[m], pooled_rel[m], pooled_ulp[m]));
    report.overall.back().worst = WorstSample{};
    report.overall.back().worst_finite = WorstSample{};
  }
  return report;
}

StressReport run_stress(const StressOptions& opt) {
  StressOptions whole = opt;
  whole.shard = ShardSpec{};
  return finish_stress(whole, {run_stress_part(whole)});
}

}  // namespace rayint
