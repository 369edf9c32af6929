#pragma once
// The quadratures NeRF-style renderers use for the emission-absorption integral (Williams & Max
// 1992 Eq. 4; Max 1995 Eq. 1), as methods and on explicit samples:
//
//   nerf     piecewise-constant density and colour per sample interval (Mildenhall et al. 2020,
//            "NeRF", Eq. 3):  C = sum_i T_i alpha_i c_i,  alpha_i = 1 - exp(-sigma_i delta_i),
//            T_i = prod_{j<i} (1 - alpha_j), i.e. Max 1995's front-to-back alpha compositing
//            with the opacity of a homogeneous step;
//   pl_nerf  piecewise-linear density between samples with its exact transmittance and the
//            interval's midpoint colour (Uy et al. 2023, "NeRF Revisited: Fixing Quadrature
//            Instability in Volume Rendering", NeurIPS): alpha_i = 1 - exp(-(sigma_i +
//            sigma_{i+1}) delta_i / 2), colour (c_i + c_{i+1}) / 2.
//
// Conventions of the common implementations (the sample layout and the last interval) and the
// measured errors are in nerf.cpp.
#include <cstddef>

#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/riemann.hpp"

namespace rayint {

// Front-to-back compositing from the eye (Max 1995; NeRF Eq. 3) of one channel: each step adds
// T * alpha * colour and multiplies T by 1 - alpha, with alpha = 1 - exp(-tau) from
// step_opacity (one transcendental call, ~1 ulp; riemann.hpp).
struct FrontToBack {
  double emission = 0.0;       // light emitted toward the eye so far
  double transmittance = 1.0;  // T: fraction of light from behind the steps so far that passes
  void add(double tau, double colour) {
    const StepOpacity o = step_opacity(tau);
    emission += transmittance * o.alpha * colour;
    transmittance *= o.transparency;
  }
};

struct CompositeResult {
  double emission = 0.0;       // sum_i T_i alpha_i c_i, without the background
  double transmittance = 1.0;  // T after the last step
};

// nerf on explicit samples, ordered from the eye outward: sample i has density sigma[i] >= 0,
// colour colour[i] and interval length delta[i] >= 0 (count entries each).
CompositeResult nerf_composite(const double* sigma, const double* colour, const double* delta,
                               std::size_t count);

// pl_nerf on explicit samples, ordered from the eye outward: `intervals` intervals of length
// delta[i] between samples i and i + 1 (sigma and colour hold intervals + 1 entries). With
// mid_colour the interval's colour is (c_i + c_{i+1}) / 2 (PL-NeRF "midpoint"), otherwise c_i,
// the eye-side sample (PL-NeRF "left").
CompositeResult pl_nerf_composite(const double* sigma, const double* colour, const double* delta,
                                  std::size_t intervals, bool mid_colour);

// Where `nerf` samples each of the n intervals of a segment.
enum class NerfSampleAt {
  mid,   // the interval's midpoint (nerfstudio's bin centre; the default)
  near,  // the interval's eye-side end: NeRF 2020's t_i with delta_i = t_{i+1} - t_i
};

struct NerfOptions {
  int n = 64;                              // intervals per segment
  NerfSampleAt at = NerfSampleAt::mid;     // nerf only
  bool last_inf = false;                   // nerf only: NeRF 2020's extra far sample, delta 1e10
  bool mid_colour = true;                  // pl_nerf only: color=mid (default) or near
};

// The delta NeRF 2020 (run_nerf.py, raw2outputs) gives its last sample.
inline constexpr double kNerfLastDelta = 1e10;

// nerf: n, at=mid|near, last=interval|inf. pl_nerf: n, color=mid|near. Throws
// std::invalid_argument for values out of range.
NerfOptions nerf_options(const MethodSpec& spec);
NerfOptions pl_nerf_options(const MethodSpec& spec);

class NerfIntegrator final : public SamplingIntegrator {
 public:
  NerfIntegrator(const TransferFunctions& tf, const NerfOptions& options, bool piecewise_linear);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  NerfOptions opt_;
  bool linear_;  // pl_nerf
};

}  // namespace rayint
