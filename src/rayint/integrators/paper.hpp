#pragma once
// Williams & Max (1992) Sec. 3.3, literally: the Mathematica output with Erfi for q2 != 0 and
// the q2 = 0 expression, in the paper's variables (t measured from the cell entry). Kept to show
// where the printed formula overflows or cancels; non-finite results are returned as they come.
#include "rayint/integrators/integrator.hpp"

namespace rayint {

// The paper's per-interval quantities for one channel (Sec. 3.3).
struct PaperInterval {
  double q1, q2, q3, q4, q5;
  double t_begin, t_end;  // t_i, t_{i+1}
};
// First term of I(t_{i+1}) (the emission on the interval), exactly as printed.
double paper_emission(const PaperInterval& iv);
// exp(-(q1 t_{i+1} + q2 t_{i+1}^2/2 - q1 t_i - q2 t_i^2/2)), as printed.
double paper_transmittance(const PaperInterval& iv);

class PaperIntegrator final : public PieceIntegrator {
 public:
  using PieceIntegrator::PieceIntegrator;
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;
};

}  // namespace rayint
