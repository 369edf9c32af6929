#pragma once
// Williams & Max (1992) Eq. 3 along a ray whose scalar is a polynomial per segment
// (model/poly_ray.hpp), by the `ode` method's Dormand-Prince 5(4) stepping; see poly_ode.cpp.
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/ode.hpp"
#include "rayint/model/poly_ray.hpp"

namespace rayint {

// Where a segment is split (distances from its far end, 0 and length included): its critical
// points and every crossing of a transfer-function breakpoint (poly::split_points in double).
std::vector<double> poly_split_points(const PolySegment& segment,
                                      const std::vector<double>& breakpoints);

class PolyOdeIntegrator {
 public:
  PolyOdeIntegrator(const TransferFunctions& tf, const OdeOptions& options);
  // Diagnostics: stats "steps", "rejected_steps", "pieces"; failure branches as `ode`.
  RayResult integrate(const PolyRay& ray, Diagnostics* diag) const;

 private:
  const TransferFunctions* tf_;
  std::vector<double> breakpoints_;
  OdeOptions opt_;
};

}  // namespace rayint
