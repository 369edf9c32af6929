#pragma once
// The error statistics every study reports (stress, sweep, gate, cells, eval timing, mesh
// render comparison), defined once:
//
//   median(v)        the middle value; for an even count the MEAN OF THE TWO MIDDLE VALUES.
//                    The textbook definition: it favours neither neighbour, and it is what the
//                    sweep and reports/README have always documented.
//   quantile(v, q)   NEAREST RANK: the ceil(q n)-th smallest value (1-based; at least the
//                    1st). A tail figure that is always one of the measured errors -- a sample
//                    that can be replayed -- never an interpolation between an outlier and a
//                    typical value, and an upper limit on it (the gate) bounds that many
//                    samples exactly. p99 = quantile(v, 0.99).
//   error_stats(v)   max, p99 and median of one set (all 0 for an empty set).
//
// Values must not be NaN (callers drop unscored entries first); +inf sorts last.
#include <vector>

namespace rayint {

// A reference value below this in magnitude counts as underflowed: relative error means nothing
// there (at and past double underflow, e.g. thick-absorber-background, or an exact 0), so such a
// value is scored by its absolute error instead (metrics/error_metrics.hpp scored_error; stress
// reports it separately, the sweep counts it in units of this floor). Chosen ~18 decades above
// the smallest normal double (2.2e-308) so that the reference's hi + lo is still resolved
// relative to it; tests/test_exact.cpp switches from its relative to its absolute criterion at
// the same 1e-290.
inline constexpr double kUnderflowFloor = 1e-290;

double median(std::vector<double> values);           // 0 for an empty set
double quantile(std::vector<double> values, double q);  // nearest rank; 0 for an empty set

inline constexpr double kP99 = 0.99;

// Order statistics of a set of errors (see the file comment). All 0 for an empty set.
struct ErrorStats {
  double max = 0.0;
  double p99 = 0.0;
  double median = 0.0;
};
ErrorStats error_stats(std::vector<double> values);

}  // namespace rayint
