#pragma once
// The per-cell approximations of Williams & Max (1992) Sec. 3.1: Eq. 5 (chromaticity constant),
// Eq. 6 (chromaticity and density constant, their cell averages), Eq. 7 (Eq. 6 as an opacity)
// and Eq. 8 (the opacity linearised). Definitions in cell_approximations.cpp.
#include <vector>

#include "rayint/integrators/integrator.hpp"

namespace rayint {

enum class CellRule { eq5, eq6, eq7, eq8 };
const char* cell_rule_name(CellRule rule);

class CellIntegrator final : public RayIntegrator {
 public:
  CellIntegrator(const TransferFunctions& tf, CellRule rule);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  const TransferFunctions& tf_;
  CellRule rule_;
  std::vector<double> breakpoints_;  // eq5 works on pieces
};

}  // namespace rayint
