#pragma once
// Partial pre-integration (Moreland & Angel 2004, as in VTK's
// vtkUnstructuredGridPartialPreIntegration): the one part of the exact piece integral that
// is not elementary, Psi = int_0^1 exp(-tau(u)) du, is read from a table over
// gamma = tau D / (1 + tau D) at the piece's two ends. See psi_table.cpp.
#include <memory>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/integrators/table_grid.hpp"

namespace rayint {

// Psi and 1 - Psi on a size x size grid of (gamma_exit, gamma_far); row = exit end (eye side),
// column = far end (model/ray.hpp). Depends only on (size, lookup), so it is shared.
class PsiTable {
 public:
  PsiTable(int size, table::Lookup lookup);
  // Shared instance per (size, lookup == floor): built on first use, thread-safe.
  static std::shared_ptr<const PsiTable> shared(int size, table::Lookup lookup);

  int size() const { return size_; }
  double gamma(int i) const;          // grid value i
  double build_seconds() const { return build_seconds_; }
  double bytes() const { return 2.0 * sizeof(double) * size_ * size_; }

  // Bound on |interpolated Psi - Psi| over the whole square for `lookup` (see psi_table.cpp):
  // the sup sits at gamma_far -> 1, where Psi ~ sqrt(pi (1 - gamma_far)/2), and scales
  // like size^{-1/2} for every lookup.
  double max_error(table::Lookup lookup) const;

  struct Value {
    double psi, one_minus_psi;
  };
  // Interpolated (per `lookup`) at optical depths tau_front D, tau_back D >= 0.
  Value lookup(double tau_exit_D, double tau_far_D, table::Lookup lookup) const;
  // The lookup and its derivatives with respect to the two depths: what automatic
  // differentiation through lookup() computes (psi_table_grad.hpp). linear: the bilinear
  // interpolant's slopes in the cell read (at a grid line, the cell above it), times
  // d gamma/dx = 1/(1 + x)^2; a coordinate clamped to the table's edge (x = inf) has slope 0;
  // nearest and floor are piecewise constant: slopes 0.
  struct ValueGrad {
    Value value;
    double dpsi_dexit = 0.0, dpsi_dfar = 0.0;    // d Psi / d x_exit, d x_far
    double domp_dexit = 0.0, domp_dfar = 0.0;    // d (1 - Psi) / d x_exit, d x_far
  };
  ValueGrad lookup_grad(double tau_exit_D, double tau_far_D, table::Lookup lookup) const;

 private:
  int size_;
  double scale_;  // grid units per unit gamma: size - 1, or size for VTK's floor grid
  std::vector<double> psi_, one_minus_psi_;
  double build_seconds_ = 0.0;
};

// gamma = x/(1 + x) for x >= 0, 1 for x = +inf.
double psi_gamma(double tau_D);

class PsiTableIntegrator final : public RayIntegrator {
 public:
  PsiTableIntegrator(const TransferFunctions& tf, int size, table::Lookup lookup);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;
  const PsiTable& table() const { return *table_; }

 private:
  PieceSplitter splitter_;
  table::Lookup lookup_;
  std::shared_ptr<const PsiTable> table_;
};

}  // namespace rayint
