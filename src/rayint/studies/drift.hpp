#pragma once
// Drift gate: a deterministic method's (or a renderer's) per-ray intensities against a committed
// baseline of its own earlier results, in units in the last place (ulps), so a change that moves
// any number by more than a stated allowance fails even when it stays within the accuracy limits
// (`rayint gate --baseline DIR`, README "Drift baselines").
//
// ulp distance of two doubles a, b: the number of representable doubles between them, i.e. the
// difference of their positions in the ordered sequence of finite doubles (so 0 and -0 are 0 ulps
// apart and the smallest subnormal is 1 ulp from 0). Two NaNs, or two equal infinities, are 0
// apart; a non-finite value against a finite one (or against the other infinity) is +inf apart.
#include <map>
#include <string>
#include <vector>

#include "rayint/model/transfer_function.hpp"  // Rgb

namespace rayint {

double ulp_distance(double a, double b);

// The per-ray intensities of one method (or one renderer): case name -> one Rgb per ray, in the
// case's order; a non-finite result is kept as is (NaN for a method that threw).
using RayResults = std::map<std::string, std::vector<Rgb>>;

struct Baseline {
  std::string method;        // the method's label ("riemann:n=64") or "candidates"
  std::string generated_by;  // the command that wrote it
  RayResults cases;
};

struct DriftResult {
  double max_ulps = 0.0;  // largest ulp distance over every case, ray and channel
  long values = 0;        // channels compared
  long drifted = 0;       // channels farther apart than the allowance
  std::string where;      // "case C ray R channel g: baseline X, now Y" at the largest distance
  std::string mismatch;   // non-empty when the cases or ray counts differ (then the check fails)
};

// Compares `now` with `baseline` case by case; `allowance` only counts `drifted`.
DriftResult compare_to_baseline(const Baseline& baseline, const RayResults& now, double allowance);

}  // namespace rayint
