// sweep.cpp -- the accuracy/cost sweep (definitions of every number in sweep.hpp's comment).
//
// Order of work: (1) the 50-digit reference of every ray of every case, in parallel
// (reference_rays), once; (2) for each setting of each axis, for each case: build the integrator,
// then for each ray integrate once (diag = nullptr) to score it against the stored reference and
// time it with time_per_ray (single thread, no reference, no diagnostics). Budgets are checked
// before every ray; a setting interrupted by a budget is dropped whole.
#include "rayint/studies/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <stdexcept>

#include "rayint/core/parallel.hpp"     // hardware_threads
#include "rayint/core/statistics.hpp"  // median
#include "rayint/mesh/quadratic_methods.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<std::string> powers_of_two(int lo_exp, int hi_exp) {
  std::vector<std::string> v;
  for (int e = lo_exp; e <= hi_exp; ++e) v.push_back(std::to_string(1L << e));
  return v;
}

std::vector<std::string> decades(int from_exp, int to_exp) {  // 1e-<from> .. 1e-<to>
  std::vector<std::string> v;
  for (int e = from_exp; e <= to_exp; ++e) v.push_back("1e-" + std::to_string(e));
  return v;
}

double mean_of(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// Which budget, if any, has run out.
struct Budget {
  Clock::time_point sweep_start, method_start;
  double max_seconds = 0.0, method_max_seconds = 0.0;
  bool exempt = false;  // exact: the unit of cost always runs in full
  std::string exhausted() const {
    if (exempt) return {};
    char buf[96];
    if (max_seconds > 0 && seconds_since(sweep_start) > max_seconds) {
      std::snprintf(buf, sizeof buf, "sweep budget of %g s (--max-seconds) ran out", max_seconds);
      return buf;
    }
    if (method_max_seconds > 0 && seconds_since(method_start) > method_max_seconds) {
      std::snprintf(buf, sizeof buf, "per-method budget of %g s (--method-seconds) ran out",
                    method_max_seconds);
      return buf;
    }
    return {};
  }
};

// The rays of case ci that a part owns: [begin, end) of the case's rays.
struct CaseCover {
  std::size_t begin = 0, end = 0;
  bool constructs = false;  // the part builds the case's integrator (it covers a ray, or the
                            // case has none and this is the first part)
};

std::vector<CaseCover> case_covers(const std::vector<Case>& cases, const ShardSpec& shard) {
  std::size_t total = 0;
  for (const Case& c : cases) total += c.rays.size();
  const IndexRange mine = shard_range(total, shard);
  std::vector<CaseCover> out;
  std::size_t offset = 0;
  for (const Case& c : cases) {
    CaseCover cv;
    cv.begin = std::min(std::max(mine.begin, offset), offset + c.rays.size()) - offset;
    cv.end = std::max(std::min(mine.end, offset + c.rays.size()), offset) - offset;
    if (cv.end < cv.begin) cv.end = cv.begin;
    cv.constructs = cv.end > cv.begin || (c.rays.empty() && shard.index == 0);
    out.push_back(cv);
    offset += c.rays.size();
  }
  return out;
}

// Measures one setting on the covered rays of every case: integrate once (diag = nullptr) to
// score against the stored reference (refs[ci][r - cover.begin]), then time the ray. Returns
// false (and the reason) if a budget ran out before it finished.
bool measure_samples(const MethodSpec& spec, const std::vector<Case>& cases,
                     const std::vector<CaseCover>& covers,
                     const std::vector<std::vector<ReferenceRay>>& refs, const SweepOptions& opt,
                     const Budget& budget, SweepSettingSamples& out, std::string& stopped) {
  const auto t0 = Clock::now();
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const CaseCover& cover = covers[ci];
    SweepCaseSamples cs;
    cs.first_ray = cover.begin;
    cs.covered = cover.end - cover.begin;
    if (!cover.constructs) {
      out.cases.push_back(std::move(cs));
      continue;
    }
    std::unique_ptr<RayIntegrator> integrator;
    try {
      const auto setup_start = Clock::now();
      integrator = make_case_integrator(spec, c.transfer);  // exact takes quadratic chords
      cs.setup_seconds = seconds_since(setup_start);
    } catch (const std::exception& e) {
      cs.setup_failed = true;
      cs.setup_failure = e.what();
      out.cases.push_back(std::move(cs));
      continue;
    }
    for (std::size_t r = cover.begin; r < cover.end; ++r) {
      stopped = budget.exhausted();
      if (!stopped.empty()) return false;
      SweepRaySample sample;
      RayResult result;
      try {
        result = integrator->integrate(c.rays[r], nullptr);
      } catch (const std::exception& e) {
        sample.failed = true;
        sample.failure = e.what();
        cs.rays.push_back(std::move(sample));
        continue;
      }
      for (int ch = 0; ch < kChannels; ++ch) {
        sample.error[ch] = scored_error(result.intensity[ch], refs[ci][r - cover.begin].intensity[ch]);
        if (!std::isfinite(result.intensity[ch])) sample.nonfinite |= 1u << ch;
      }
      if (opt.timing.measure_time) sample.seconds = time_per_ray(*integrator, c.rays[r], opt.timing);
      cs.rays.push_back(std::move(sample));
    }
    out.cases.push_back(std::move(cs));
  }
  out.wall_seconds = seconds_since(t0);
  return true;
}

// The setting's scores from what it measured on every ray (the parts' samples joined case by
// case, in ray order): the definitions of sweep.hpp.
void summarise_setting(const std::vector<Case>& cases, const SweepSettingSamples& samples,
                       const SweepOptions& opt, SettingResult& out) {
  std::vector<double> all_errors, all_times;
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const SweepCaseSamples& sc = samples.cases[ci];
    CaseScore cs;
    cs.name = c.name;
    cs.rays = c.rays.size();
    out.rays += c.rays.size();
    out.setup_seconds += sc.setup_seconds;
    if (sc.setup_failed) {
      cs.failed_rays = sc.covered;
      out.failed_rays += sc.covered;
      if (out.failure.empty()) out.failure = c.name + ": " + sc.setup_failure;
      out.per_case.push_back(std::move(cs));
      continue;
    }
    std::vector<double> case_errors, case_times;
    for (std::size_t k = 0; k < sc.rays.size(); ++k) {
      const SweepRaySample& sample = sc.rays[k];
      const std::size_t r = sc.ray_numbers.empty() ? sc.first_ray + k : sc.ray_numbers[k];
      if (sample.failed) {
        ++cs.failed_rays;
        ++out.failed_rays;
        if (out.failure.empty())
          out.failure = c.name + " ray " + std::to_string(r) + ": " + sample.failure;
        continue;
      }
      for (int ch = 0; ch < kChannels; ++ch) {
        const double e = sample.error[ch];
        if (sample.nonfinite & (1u << ch)) {
          ++cs.nonfinite;
          ++out.nonfinite;
        }
        if (case_errors.empty() || e > cs.max_error) cs.max_error = e;
        if (all_errors.empty() || e > out.max_error) {
          out.max_error = e;
          out.worst_case = c.name;
          out.worst_ray = r;
          out.worst_channel = ch;
        }
        case_errors.push_back(e);
        all_errors.push_back(e);
      }
      if (opt.timing.measure_time) {
        case_times.push_back(sample.seconds);
        all_times.push_back(sample.seconds);
      }
    }
    cs.median_error = median(case_errors);
    cs.seconds_per_ray = mean_of(case_times);
    out.per_case.push_back(std::move(cs));
  }
  out.channels = all_errors.size();
  out.median_error = median(all_errors);
  out.seconds_per_ray = mean_of(all_times);
  out.median_seconds_per_ray = median(all_times);
  out.wall_seconds = samples.wall_seconds;
}

// Joins the parts' samples of one setting: case by case, the parts' rays in shard order.
SweepSettingSamples join_samples(const std::vector<const SweepSettingSamples*>& parts, std::size_t n_cases) {
  SweepSettingSamples out;
  out.cases.resize(n_cases);
  std::vector<std::size_t> next(n_cases, 0);  // the first ray after the parts joined so far
  for (const SweepSettingSamples* p : parts) {
    if (p->cases.size() != n_cases)
      throw std::invalid_argument("bench merge: a part holds " + std::to_string(p->cases.size()) +
                                  " cases, the run " + std::to_string(n_cases));
    out.wall_seconds += p->wall_seconds;
    for (std::size_t ci = 0; ci < n_cases; ++ci) {
      const SweepCaseSamples& from = p->cases[ci];
      SweepCaseSamples& to = out.cases[ci];
      if (from.covered == 0 && !from.setup_failed) continue;
      if (to.covered == 0 && !to.setup_failed) {
        to.first_ray = from.first_ray;
      } else if (from.first_ray < next[ci]) {
        throw std::invalid_argument("bench merge: case " + std::to_string(ci) + ": a part starts at ray " +
                                    std::to_string(from.first_ray) + ", before the end of the previous one (" +
                                    std::to_string(next[ci]) + ")");
      }
      next[ci] = from.first_ray + from.covered;
      if (from.setup_failed && !to.setup_failed) {
        to.setup_failed = true;
        to.setup_failure = from.setup_failure;
      }
      if (!from.setup_failed && from.rays.size() != from.covered)
        throw std::invalid_argument("bench merge: case " + std::to_string(ci) + ": a part covers " +
                                    std::to_string(from.covered) + " rays but holds " +
                                    std::to_string(from.rays.size()));
      for (std::size_t k = 0; k < from.rays.size(); ++k) to.ray_numbers.push_back(from.first_ray + k);
      to.covered += from.covered;
      to.setup_seconds += from.setup_seconds;
      to.rays.insert(to.rays.end(), from.rays.begin(), from.rays.end());
    }
  }
  return out;
}

// The case-set figures of a result (names, files, rays, pieces).
void describe_cases(const std::vector<Case>& cases, SweepResult& res) {
  for (const Case& c : cases) {
    std::size_t pieces = 0;
    for (const Ray& ray : c.rays) pieces += split_ray(c.transfer, ray).size();
    res.case_names.push_back(c.name);
    res.case_files.push_back(c.source);
    res.case_rays.push_back(c.rays.size());
    res.case_pieces.push_back(pieces);
    res.rays += c.rays.size();
    res.pieces += pieces;
  }
}

// The references of the covered rays of every case, in parallel over the rays of each case.
std::vector<std::vector<ReferenceRay>> covered_references(const std::vector<Case>& cases,
                                                          const std::vector<CaseCover>& covers,
                                                          const SweepOptions& opt,
                                                          Clock::time_point start) {
  std::vector<std::vector<ReferenceRay>> refs;
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const CaseCover& cv = covers[ci];
    if (cv.begin == 0 && cv.end == c.rays.size()) {
      refs.push_back(reference_rays(c, opt.timing.threads));
    } else {
      Case part;  // the covered rays only
      part.name = c.name;
      part.source = c.source;
      part.transfer = c.transfer;
      part.rays.assign(c.rays.begin() + static_cast<std::ptrdiff_t>(cv.begin),
                       c.rays.begin() + static_cast<std::ptrdiff_t>(cv.end));
      refs.push_back(part.rays.empty() ? std::vector<ReferenceRay>{} : reference_rays(part, opt.timing.threads));
    }
    if (opt.progress) {
      SweepProgress p;
      p.stage = SweepProgress::Stage::reference;
      p.what = c.name;
      p.done = ci + 1;
      p.total = cases.size();
      p.elapsed_seconds = seconds_since(start);
      opt.progress(p);
    }
  }
  return refs;
}

}  // namespace

std::array<double, 3> load_average() {
  std::array<double, 3> out{-1.0, -1.0, -1.0};
  double l[3];
  if (getloadavg(l, 3) == 3) out = {l[0], l[1], l[2]};
  return out;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}


std::vector<MethodSpec> SweepAxis::settings() const {
  if (knob.empty()) return {parse_method_spec(method)};
  std::vector<MethodSpec> out;
  for (const auto& v : values) out.push_back(parse_method_spec(method + ":" + knob + "=" + v));
  return out;
}

namespace {
std::vector<SweepAxis>& mutable_sweep_table() {
  static std::vector<SweepAxis> table = {
      {"exact", "", {}},
      {"paper", "", {}},
      {"eq5", "", {}},
      {"eq6", "", {}},
      {"eq7", "", {}},
      {"eq8", "", {}},
      {"particle", "", {}},
      {"riemann", "n", powers_of_two(0, 16)},           // 1 .. 65536 samples per segment
      {"rk4", "n", powers_of_two(0, 16)},               // 1 .. 65536 steps per segment
      {"ode", "rtol", decades(2, 13)},                  // 1e-2 .. 1e-13
      {"preintegrated", "size", powers_of_two(5, 11)},  // 32 .. 2048 entries per axis
      {"psi_table", "size", powers_of_two(5, 11)},      // 32 .. 2048 entries
      {"nerf", "n", powers_of_two(0, 16)},              // 1 .. 65536 samples per segment
      {"pl_nerf", "n", powers_of_two(0, 16)},           // 1 .. 65536 intervals per segment
  };
  return table;
}
}  // namespace

const std::vector<SweepAxis>& sweep_table() { return mutable_sweep_table(); }

void register_sweep_axis(const SweepAxis& axis) { mutable_sweep_table().push_back(axis); }

std::vector<SweepAxis> select_sweep_axes(const std::vector<std::string>& methods) {
  const auto& table = sweep_table();
  for (const auto& name : methods) {
    const bool known = std::any_of(table.begin(), table.end(),
                                   [&](const SweepAxis& a) { return a.method == name; });
    if (!known) {
      std::string list;
      for (const auto& a : table) list += (list.empty() ? "" : ", ") + a.method;
      throw std::invalid_argument("bench: unknown method '" + name +
                                  "' (the sweep table has: " + list + ")");
    }
  }
  std::vector<SweepAxis> out;
  for (const auto& a : table) {
    const bool wanted = methods.empty() || a.method == "exact" ||
                        std::find(methods.begin(), methods.end(), a.method) != methods.end();
    if (wanted) out.push_back(a);
  }
  return out;
}

const char* statistic_name(ErrorStatistic s) { return s == ErrorStatistic::max ? "max" : "median"; }

std::optional<std::size_t> cheapest_setting(const MethodSweep& m, double target,
                                            ErrorStatistic statistic) {
  const auto qualifies = [&](const SettingResult& s) {
    const double e = statistic == ErrorStatistic::max ? s.max_error : s.median_error;
    return s.complete() && e <= target;
  };
  std::optional<std::size_t> fastest;
  for (std::size_t i = 0; i < m.settings.size(); ++i)
    if (qualifies(m.settings[i]) &&
        (!fastest || m.settings[i].seconds_per_ray < m.settings[*fastest].seconds_per_ray))
      fastest = i;
  if (!fastest) return fastest;
  // Ties within timing noise go to the earliest (smallest-knob) setting.
  const double limit = m.settings[*fastest].seconds_per_ray * (1.0 + kSweepTimeTieBand);
  for (std::size_t i = 0; i < m.settings.size(); ++i)
    if (qualifies(m.settings[i]) && m.settings[i].seconds_per_ray <= limit) return i;
  return fastest;
}

std::vector<TargetChoice> target_table(const std::vector<MethodSweep>& methods,
                                       double exact_seconds_per_ray,
                                       const std::vector<double>& targets) {
  std::vector<TargetChoice> out;
  for (double target : targets)
    for (ErrorStatistic stat : {ErrorStatistic::max, ErrorStatistic::median})
      for (const MethodSweep& m : methods) {
        TargetChoice t;
        t.target = target;
        t.statistic = stat;
        t.method = m.method;
        t.truncated = m.truncated;
        if (const auto i = cheapest_setting(m, target, stat)) {
          const SettingResult& s = m.settings[*i];
          t.reached = true;
          t.label = s.label;
          t.error = stat == ErrorStatistic::max ? s.max_error : s.median_error;
          t.seconds_per_ray = s.seconds_per_ray;
          t.cost_vs_exact =
              exact_seconds_per_ray > 0 ? s.seconds_per_ray / exact_seconds_per_ray : 0.0;
        }
        out.push_back(t);
      }
  return out;
}

namespace {
// exact's cost (the unit of every cost multiple) and the target table.
void finish_targets(SweepResult& res) {
  for (const MethodSweep& m : res.methods)
    if (m.method == "exact" && !m.settings.empty() && m.settings.front().complete())
      res.exact_seconds_per_ray = m.settings.front().seconds_per_ray;
  res.targets = target_table(res.methods, res.exact_seconds_per_ray, sweep_targets());
}
}  // namespace

SweepResult run_sweep(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                      const SweepOptions& opt) {
  SweepResult res;
  res.timing = opt.timing;
  res.max_seconds = opt.max_seconds;
  res.method_max_seconds = opt.method_max_seconds;
  res.hardware_threads = hardware_threads();
  res.started_at = utc_now();
  res.load_start = load_average();
  const auto start = Clock::now();

  // (1) references, once per ray, parallel over the rays of each case.
  describe_cases(cases, res);
  const std::vector<CaseCover> covers = case_covers(cases, ShardSpec{});
  const std::vector<std::vector<ReferenceRay>> refs = covered_references(cases, covers, opt, start);
  res.reference_seconds = seconds_since(start);

  // (2) every setting, scored against the stored references and timed.
  std::size_t total = 0, done = 0;
  for (const auto& a : axes) total += a.knob.empty() ? 1 : a.values.size();
  Budget budget;
  budget.sweep_start = Clock::now();
  budget.max_seconds = opt.max_seconds;
  budget.method_max_seconds = opt.method_max_seconds;
  for (const SweepAxis& axis : axes) {
    MethodSweep m;
    m.method = axis.method;
    m.knob = axis.knob;
    budget.method_start = Clock::now();
    budget.exempt = axis.method == "exact";
    const std::vector<MethodSpec> specs = axis.settings();
    for (std::size_t k = 0; k < specs.size(); ++k) {
      SettingResult s;
      s.label = specs[k].label();
      s.knob_value = axis.knob.empty() ? "" : axis.values[k];
      std::string stopped = m.truncated ? m.truncation : budget.exhausted();
      SweepSettingSamples samples;
      if (stopped.empty() && measure_samples(specs[k], cases, covers, refs, opt, budget, samples, stopped)) {
        summarise_setting(cases, samples, opt, s);
        m.settings.push_back(std::move(s));
        ++done;
        if (opt.progress) {
          SweepProgress p;
          p.stage = SweepProgress::Stage::setting;
          p.what = m.settings.back().label;
          p.done = done;
          p.total = total;
          p.elapsed_seconds = seconds_since(start);
          p.setting = &m.settings.back();
          opt.progress(p);
        }
        continue;
      }
      // A budget ran out: this and every later setting of the method are skipped.
      m.truncated = true;
      m.truncation = stopped;
      m.skipped.push_back(s.label);
      ++done;
      if (!res.truncated) {
        res.truncated = true;
        res.truncation = axis.method + ": " + stopped;
      }
      if (opt.progress) {
        SweepProgress p;
        p.stage = SweepProgress::Stage::skipped;
        p.what = s.label;
        p.done = done;
        p.total = total;
        p.elapsed_seconds = seconds_since(start);
        p.reason = stopped;
        opt.progress(p);
      }
    }
    res.methods.push_back(std::move(m));
  }
  res.measure_seconds = seconds_since(budget.sweep_start);
  res.load_end = load_average();

  finish_targets(res);
  return res;
}

std::vector<IndexRange> sweep_shard_rays(const std::vector<Case>& cases, const ShardSpec& shard) {
  std::vector<IndexRange> out;
  for (const CaseCover& cv : case_covers(cases, shard)) out.push_back({cv.begin, cv.end});
  return out;
}

SweepPart run_sweep_part(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                         const SweepOptions& opt, const ShardSpec& shard) {
  if (opt.max_seconds > 0 || opt.method_max_seconds > 0)
    throw std::invalid_argument(
        "--shard: a sharded bench cannot have a time budget (--max-seconds, --method-seconds): "
        "what it measures would depend on the clock");
  SweepPart part;
  part.hardware_threads = hardware_threads();
  part.started_at = utc_now();
  part.load_start = load_average();
  const auto start = Clock::now();
  const std::vector<CaseCover> covers = case_covers(cases, shard);
  const std::vector<std::vector<ReferenceRay>> refs = covered_references(cases, covers, opt, start);
  part.reference_seconds = seconds_since(start);
  const auto measure_start = Clock::now();
  const Budget budget;  // none
  std::size_t total = 0, done = 0;
  for (const auto& a : axes) total += a.knob.empty() ? 1 : a.values.size();
  for (const SweepAxis& axis : axes) {
    part.methods.emplace_back();
    for (const MethodSpec& spec : axis.settings()) {
      SweepSettingSamples samples;
      std::string stopped;
      measure_samples(spec, cases, covers, refs, opt, budget, samples, stopped);
      ++done;
      if (opt.progress) {
        SettingResult shard_figures;  // the shard's rays only, for the progress line
        summarise_setting(cases, samples, opt, shard_figures);
        SweepProgress p;
        p.setting = &shard_figures;
        p.stage = SweepProgress::Stage::setting;
        p.what = spec.label() + " (shard " + shard.label() + ")";
        p.done = done;
        p.total = total;
        p.elapsed_seconds = seconds_since(start);
        opt.progress(p);
      }
      part.methods.back().push_back(std::move(samples));
    }
  }
  part.measure_seconds = seconds_since(measure_start);
  part.load_end = load_average();
  return part;
}

SweepResult finish_sweep(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                         const SweepOptions& opt, const std::vector<SweepPart>& parts) {
  if (parts.empty()) throw std::invalid_argument("bench merge: no parts");
  SweepResult res;
  res.timing = opt.timing;
  res.max_seconds = opt.max_seconds;
  res.method_max_seconds = opt.method_max_seconds;
  res.started_at = parts.front().started_at;
  res.load_start = parts.front().load_start;
  res.load_end = parts.back().load_end;
  for (const SweepPart& p : parts) {
    res.hardware_threads = std::max(res.hardware_threads, p.hardware_threads);
    res.reference_seconds += p.reference_seconds;
    res.measure_seconds += p.measure_seconds;
    if (p.methods.size() != axes.size())
      throw std::invalid_argument("bench merge: a part holds " + std::to_string(p.methods.size()) +
                                  " methods, the run " + std::to_string(axes.size()));
  }
  describe_cases(cases, res);
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const SweepAxis& axis = axes[a];
    MethodSweep m;
    m.method = axis.method;
    m.knob = axis.knob;
    const std::vector<MethodSpec> specs = axis.settings();
    for (std::size_t k = 0; k < specs.size(); ++k) {
      std::vector<const SweepSettingSamples*> mine;
      for (const SweepPart& p : parts) {
        if (p.methods[a].size() != specs.size())
          throw std::invalid_argument("bench merge: " + axis.method + ": a part holds " +
                                      std::to_string(p.methods[a].size()) + " settings, the run " +
                                      std::to_string(specs.size()));
        mine.push_back(&p.methods[a][k]);
      }
      SettingResult s;
      s.label = specs[k].label();
      s.knob_value = axis.knob.empty() ? "" : axis.values[k];
      summarise_setting(cases, join_samples(mine, cases.size()), opt, s);
      m.settings.push_back(std::move(s));
    }
    res.methods.push_back(std::move(m));
  }
  finish_targets(res);
  return res;
}

}  // namespace rayint
