#pragma once
// Convergence of a renderer with its sample distance (`rayint converge`): per-pixel error
// statistics against the exact image, and the observed order of convergence (Etiene et al.,
// verification of volume rendering: a renderer whose observed order is below the expected one
// has a bug). Pure numerics on numbers the caller measured; see convergence.cpp.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace rayint {

struct PixelErrorStats {
  bool ok = false;  // false: no pixels (the candidate failed)
  double median = 0.0, p95 = 0.0, max = 0.0;
};
// Of per-pixel errors (any order); p95 is the nearest-rank 95th percentile.
PixelErrorStats pixel_error_stats(std::vector<double> errors);

struct OrderFit {
  bool ok = false;          // false: fewer than 2 usable points
  std::string reason;       // why not ok
  double order = 0.0;       // least-squares slope of log(error) on log(step)
  std::size_t first = 0;    // the range used: indices into the (step-sorted, coarse -> fine) input
  std::size_t last = 0;
  std::vector<double> local_orders;  // log(e_i / e_{i+1}) / log(h_i / h_{i+1}), coarse -> fine
};
// steps strictly decreasing (coarse -> fine); errors > 0 where usable. The asymptotic range: the
// finest points whose error is above `floor` (below it the exact image's own error or rounding
// dominates), and of those the longest run from the finest one back toward coarse steps whose
// local orders stay within `spread` of the finest pair's (the pre-asymptotic coarse steps are
// dropped). Failed points (error NaN) end the run.
OrderFit observed_order(const std::vector<double>& steps, const std::vector<double>& errors, double floor,
                        double spread = 0.5);

}  // namespace rayint

namespace rayint {

// One of a step's worst pixels: where, how far off, and the ray that replays it.
struct WorstPixel {
  int x = 0, y = 0;                  // pixel, y down from the top (rayint's row order)
  double error = 0.0;                // largest channel difference
  std::array<double, 3> candidate{}, exact{};
  std::array<double, 3> origin{}, direction{};  // the pixel centre's ray (camera scenes)
};

// One candidate image at one step.
struct ConvergenceRow {
  double step = 0.0;
  std::string candidate;   // the method or command that made it
  bool failed = false;     // the command failed or its image could not be read / compared
  std::string failure;     // why (one line)
  PixelErrorStats error;   // per-pixel error against the exact image (max over channels)
  double change_from_finest = 0.0;  // max per-pixel difference to the finest step's image
  std::vector<WorstPixel> worst;     // --worst N: the N largest errors, largest first
  std::string error_map;             // --error-map-dir: the .npy written for this step
};

struct ConvergenceResult {
  std::vector<ConvergenceRow> rows;  // coarse -> fine
  double peak = 0.0;                 // largest channel value of the exact image
  double floor = 0.0;                // errors at or below it are not fitted
  OrderFit median_fit, p95_fit, max_fit;
  std::string metric = "median";     // the statistic gated on
  bool invariant = false;            // every image within invariance_tolerance * peak of the finest
  double invariance_tolerance = 0.0;
  bool has_expectation = false;
  double expected_order = 0.0, order_tolerance = 0.0;
  bool passed = true;                // expectation met and no row failed

  const OrderFit& gated_fit() const {
    return metric == "max" ? max_fit : metric == "p95" ? p95_fit : median_fit;
  }
};

// Fills the fits, invariance and verdict of `r` from its rows (rows, peak, floor, metric,
// invariance_tolerance and the expectation set by the caller).
void conclude(ConvergenceResult& r);

}  // namespace rayint
