#pragma once
// Pre-integrated transfer functions (Engel, Kraus & Ertl 2001; the 3-D form with the segment
// length as a third axis after Roettger, Kraus & Ertl 2000): the ray integral of a step whose
// scalar runs linearly from s_far to s_exit is read from a table built once per case with the
// exact kernel. See preintegrated.cpp for the table's contents, lookups and error sources.
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/table_grid.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

struct PreintegratedOptions {
  int size = 256;                         // scalar grid points per axis (>= 2)
  table::Lookup lookup = table::Lookup::linear;
  int dims = 2;                           // 2: fixed step; 3: length axis too
  double step = 0x1p-6;                   // dims = 2: the sampling distance D
  double max_length = 4.0;                // dims = 3: longest length on the axis
  int lengths = 0;                        // dims = 3: planes on the length axis (0: auto)
};

// Reads a validated spec; throws std::invalid_argument for combinations that mean nothing
// (step with dims=3, ...) or a table over kPreintegratedMaxTableBytes.
PreintegratedOptions preintegrated_options(const MethodSpec& spec);
// Bytes of the table these options build: size^2 entries x 3 channels x (1 + planes) doubles.
double preintegrated_table_bytes(const PreintegratedOptions& o);

// Number of steps of length `step` a segment of `length` is cut into: ceil(length/step), except
// that a remainder below 1e-9 step (length/step an integer up to rounding) adds no step.
double preintegrated_step_count(double length, double step);

// Limits (their origin is documented in preintegrated.cpp).
inline constexpr long kPreintegratedMaxLookupsPerRay = 1L << 22;
inline constexpr double kPreintegratedMaxTableBytes = 1024.0 * 1024.0 * 1024.0;

class PreintegratedIntegrator final : public RayIntegrator {
 public:
  PreintegratedIntegrator(const TransferFunctions& tf, const PreintegratedOptions& options);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;
  // What automatic differentiation through this renderer computes (issue 28): the derivative of
  // integrate()'s steps, lookups and table build with respect to the background, every segment's
  // length and end scalars, and the value and position of every transfer-function node -- except
  // that the table's scalar range [scalar_lo, scalar_hi] is held fixed (see preintegrated_grad.cpp).
  // `tf` must be the functions the table was built from. The forward intensity is integrate()'s.
  RayGradient gradient(const TransferFunctions& tf, const Ray& ray) const;

  const PreintegratedOptions& options() const { return opt_; }
  double build_seconds() const { return build_seconds_; }
  double table_bytes() const;
  double scalar_lo() const { return s_lo_; }
  double scalar_hi() const { return s_hi_; }
  double plane_length(int k) const { return plane_length_[k]; }
  int planes() const { return static_cast<int>(plane_length_.size()); }

 private:
  struct StepOptics {
    Rgb depth, transmittance, emission;  // optical depth tau, e^{-tau}, emission
  };
  StepOptics lookup(double s_far, double s_exit, double length) const;

  // One step of a segment as integrate() cuts it: scalars s0 (far) and s1 (exit), length l, and
  // their derivatives with respect to the segment's (scalar_far, scalar_exit, length).
  struct Cut {
    std::size_t segment = 0;
    double s0 = 0.0, s1 = 0.0, l = 0.0;
    double s0_far = 1.0, s0_exit = 0.0, s0_length = 0.0;  // d s0 / d (scalar_far, scalar_exit, length)
    double s1_far = 0.0, s1_exit = 1.0, s1_length = 0.0;
    double l_length = 1.0;                                // d l / d length
  };
  // Calls f(const Cut&) for every step of the ray far -> near; the cut is integrate()'s and
  // gradient()'s (one definition). Throws std::runtime_error over the lookup budget.
  template <class F>
  void for_each_step(const Ray& ray, F&& f) const;
  // Scalar of grid point i (0 .. size-1) of both scalar axes.
  double grid_scalar(int i) const;
  // Lookup budget check; returns the number of lookups.
  double count_lookups(const Ray& ray) const;

  PreintegratedOptions opt_;
  double s_lo_ = 0.0, s_hi_ = 1.0, inv_ds_ = 1.0;
  std::vector<double> plane_length_;  // L_k; one plane (L = step) for dims = 2
  double inv_dL_ = 0.0;               // 1 / (L_{k+1} - L_k), dims = 3
  // rate_[c]: mean density over the step's scalar path (optical depth per unit length);
  // q_[k][c]: emission per unit length corrected for self-absorption at length L_k.
  // Each is size x size, row = s_far, column = s_exit.
  std::vector<double> rate_[kChannels];
  std::vector<std::vector<double>> q_;  // [plane * kChannels + c]
  double build_seconds_ = 0.0;
};

template <class F>
void PreintegratedIntegrator::for_each_step(const Ray& ray, F&& f) const {
  // Cut length per segment: D for dims = 2, max_length for dims = 3; see preintegrated.cpp.
  const double cut = opt_.dims == 2 ? opt_.step : opt_.max_length;
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(seg.length > 0.0)) continue;
    const long n = static_cast<long>(preintegrated_step_count(seg.length, cut));
    // dims = 2: n - 1 steps of D then the rest; dims = 3: n equal parts.
    const double part = opt_.dims == 2 ? opt_.step : seg.length / static_cast<double>(n);
    const double ds = seg.scalar_exit - seg.scalar_far;
    Cut c;
    c.segment = j;
    c.s1 = seg.scalar_far;
    c.s1_far = 1.0;
    c.s1_exit = 0.0;
    for (long k = 0; k < n; ++k) {
      const bool last = k + 1 == n;
      c.s0 = c.s1;
      c.s0_far = c.s1_far;
      c.s0_exit = c.s1_exit;
      c.s0_length = c.s1_length;
      c.l = last ? seg.length - part * static_cast<double>(n - 1) : part;
      // dims = 2: l = D (no length in it) or L - (n-1) D; dims = 3: L/n either way.
      c.l_length = opt_.dims == 3 ? 1.0 / static_cast<double>(n) : (last ? 1.0 : 0.0);
      const double fraction = part * static_cast<double>(k + 1) / seg.length;
      c.s1 = last ? seg.scalar_exit : seg.scalar_far + ds * fraction;
      c.s1_far = last ? 0.0 : 1.0 - fraction;
      c.s1_exit = last ? 1.0 : fraction;
      // dims = 2: fraction = D (k+1)/L moves with L; dims = 3: (k+1)/n does not.
      c.s1_length = last || opt_.dims == 3 ? 0.0 : -ds * fraction / seg.length;
      f(static_cast<const Cut&>(c));
    }
  }
}

}  // namespace rayint
