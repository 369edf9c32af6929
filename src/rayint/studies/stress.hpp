#pragma once
// `rayint stress`: adversarial samples drawn regime by regime (regimes.hpp), each chosen method
// against the 50-digit reference (reference.hpp), in parallel over all cores and reproducibly:
// sample i of regime R is drawn from an engine seeded with sample_seed(seed, R, i), every
// per-sample figure lands in its own slot, and the aggregates (sums, maxima, order statistics,
// the worst sample with ties broken by the lower index) do not depend on which thread ran what.
// Returns plain structs; report/stress_json turns them into JSON, the CLI into a table.
//
// What is scored: the light reaching the eye, per channel -- emission plus the background
// attenuated through the sample (a piece-level sample's `incoming` is the ray's background).
// Piece-level samples are integrated by each method as the one-segment case piece_as_ray gives
// and compared with reference_piece; ray-level samples are compared with reference_ray.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/core/statistics.hpp"  // ErrorStats, error_stats, kUnderflowFloor
#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint {

// One value against its reference. A reference below kUnderflowFloor (core/statistics.hpp) in
// magnitude counts as underflowed: the value is scored by its absolute error (target 1e-300)
// instead of the relative error, which is meaningless there.
struct ValueScore {
  bool finite = true;
  bool underflow = false;  // |reference| < kUnderflowFloor
  double abs = 0.0;        // absolute error (+inf if not finite)
  double rel = 0.0;        // relative error; 0 where underflow
  double ulp = 0.0;        // error in ulps of the reference; 0 where underflow
};
ValueScore score_value(double x, const ExtendedValue& ref);

// One method's result on one sample (or ray), its three channels against the reference.
struct SampleScore {
  bool finite = true;      // every intensity and transmittance finite, and the method did not throw
  bool scored = false;     // finite, and at least one channel not underflowed
  bool underflow = false;  // finite, and at least one channel underflowed
  double rel = 0.0, ulp = 0.0;  // largest over the channels not underflowed
  double abs_scored = 0.0;      // likewise, absolute
  double abs_underflow = 0.0;   // largest absolute error over the underflowed channels
};
SampleScore score_sample(const RayResult& result, const std::array<ExtendedValue, kChannels>& ref,
                         bool failed);

struct StressProgress {
  long samples_done = 0, samples_total = 0;
  long pieces_done = 0, pieces_total = 0;
  double seconds = 0.0;  // since run_stress started
};

struct StressOptions {
  // Pieces to evaluate in total, split evenly over the regimes (the first count % regimes get
  // one more; every regime at least one sample). A piece-level sample is one piece; a ray-level
  // regime draws whole rays until their pieces (after splitting at breakpoints) reach its share.
  long count = 10000;
  std::uint64_t seed = 1;
  std::vector<Regime> regimes;      // empty: stress_regimes()
  std::vector<MethodSpec> methods;  // empty: exact
  unsigned threads = 0;             // 0: all cores
  // Called on the thread that called run_stress, every progress_interval_seconds and once at
  // the end; may be empty.
  std::function<void(const StressProgress&)> progress;
  double progress_interval_seconds = 2.0;
  // Shard (core/shard.hpp): the work items, most expensive first, are dealt round-robin, item k
  // to shard k mod N, so every shard gets its share of the long rays. {0, 1}: the whole run.
  ShardSpec shard;
};

// The engine seed of sample `index` of `regime`: a hash of the run seed, the regime's name and
// the index (so adding a regime or changing the count leaves the other samples unchanged).
std::uint64_t sample_seed(std::uint64_t seed, Regime regime, long index);
// Sample `index` of `regime` in the run with `seed`, exactly as run_stress drew it.
RaySample stress_sample(std::uint64_t seed, Regime regime, long index);

// The sample with the largest error of one method in one regime: a non-finite or failed one
// first; else the one with the largest relative error; else (every value underflowed) the one
// with the largest absolute error; among equals the lowest index. Its replay case is named
// stress-<regime>-<method slug> (worst) or stress-<regime>-<method slug>-finite (worst_finite).
struct WorstSample {
  bool present = false;
  long index = -1;
  std::uint64_t sample_seed = 0;
  bool non_finite = false;
  std::string failure;  // the method's exception message, if it threw
  double rel_error = 0.0, ulp_error = 0.0, abs_error = 0.0;  // largest over the channels
  Rgb value{};           // what the method returned (intensity)
  Rgb reference{};       // the reference (hi part)
  Diagnostics diagnostics;
  Case replay;           // the sample as a case file; `rayint eval` reproduces the error
  std::string file;      // where it was written (set by write_worst_cases), else empty
};

struct MethodStress {
  std::string method;  // spec label
  long scored = 0;      // finite samples with at least one channel not underflowed
  long non_finite = 0;  // samples with a non-finite intensity or transmittance, or a failure
  long failures = 0;    // of those, samples where the method threw
  long negative = 0;    // finite samples with a negative intensity or transmittance channel
  long underflow = 0;   // finite samples with at least one channel underflowed
  ErrorStats rel;       // per sample: the largest relative error over its scored channels
  ErrorStats ulp;       // likewise in ulps
  double max_abs_error_underflow = 0.0;  // over underflowed channels
  // Branch counts the method's Diagnostics reported, summed over samples (a count per piece
  // and channel for `exact`; piece-level samples have three identical channels).
  std::map<std::string, long> branches;
  WorstSample worst;
  // When `worst` is non-finite or failed: the worst of the finite samples (the one behind
  // rel.max), so that figure can be replayed too; else not present (it is `worst`).
  WorstSample worst_finite;
};

struct RegimeStress {
  std::string regime;
  bool ray_level = false;
  long samples = 0;
  long pieces = 0;
  // Largest error bound the reference claims, relative to its value (non-underflowed values).
  double max_reference_rel_bound = 0.0;
  long reference_failures = 0;        // samples where the reference threw (not scored)
  std::string reference_failure;      // the first such message (lowest index)
  std::vector<MethodStress> methods;  // in the order of StressOptions::methods
};

struct StressReport {
  std::uint64_t seed = 0;
  long count = 0;
  std::vector<std::string> methods;  // labels
  std::vector<RegimeStress> regimes;
  // Per method, pooled over all regimes (its `worst` is left empty: see the regimes).
  std::vector<MethodStress> overall;
};

// Throws std::invalid_argument for a method that cannot be built.
// run_stress(o) is finish_stress(o, {run_stress_part(o)}) with o.shard the whole run.
StressReport run_stress(const StressOptions& options);

// What a part of the run (a shard, or the whole run) carries to make every figure of the report
// exact after merging: counts and maxima (order-free), the branch counts, the worst candidates
// (a total order: severity, then the lower index) and, for the quantiles, every scored sample's
// relative and ulp error (the median and p99 of the union need all of them: 2 doubles per
// scored sample and method). Regimes in the order of the run's plan, methods in option order.
struct StressCandidate {
  int tier = -1;  // 2 non-finite or failed, 1 has scored channels, 0 underflow only, -1 none
  double error = 0.0;
  long index = -1;
  WorstSample sample;  // without its replay case (finish_stress builds it)
  bool worse_than(const StressCandidate& o) const;
};
struct StressMethodPartial {
  long scored = 0, non_finite = 0, failures = 0, underflow = 0, negative = 0;
  double max_abs_underflow = 0.0;
  std::map<std::string, long> branches;
  StressCandidate worst, worst_finite;
  std::vector<double> rel, ulp;  // per scored sample of this part
};
struct StressRegimePartial {
  long samples = 0;  // samples of this regime the part evaluated (its coverage, checked by merge)
  double max_reference_rel_bound = 0.0;
  long reference_failures = 0;
  long first_reference_failure = -1;
  std::string reference_failure;
  std::vector<StressMethodPartial> methods;
};
struct StressPartial {
  std::vector<StressRegimePartial> regimes;
};

// The part options.shard does.
StressPartial run_stress_part(const StressOptions& options);
// The samples of each regime (in the run's order) that shard `shard` of the run evaluates: what a
// part's StressRegimePartial::samples must be (merge refuses a part that covers other samples).
std::vector<long> stress_shard_samples(const StressOptions& options, const ShardSpec& shard);
// The report of the whole run from its parts (all of them, or -- a partial merge -- some).
StressReport finish_stress(const StressOptions& options, const std::vector<StressPartial>& parts);

}  // namespace rayint
