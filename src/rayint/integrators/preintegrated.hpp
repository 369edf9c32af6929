#pragma once
// Pre-integrated transfer functions (Engel, Kraus & Ertl 2001; the 3-D form with the segment
// length as a third axis after Roettger, Kraus & Ertl 2000): the ray integral of a step whose
// scalar runs linearly from s_far to s_exit is read from a table built once per case with the
// exact kernel. See preintegrated.cpp for the table's contents, lookups and error sources.
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/table_grid.hpp"

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

// Limits (their origin is documented in preintegrated.cpp).
inline constexpr long kPreintegratedMaxLookupsPerRay = 1L << 22;
inline constexpr double kPreintegratedMaxTableBytes = 1024.0 * 1024.0 * 1024.0;

class PreintegratedIntegrator final : public RayIntegrator {
 public:
  PreintegratedIntegrator(const TransferFunctions& tf, const PreintegratedOptions& options);
  RayResult integrate(const Ray& ray, Diagnostics* diag) const override;

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

}  // namespace rayint
