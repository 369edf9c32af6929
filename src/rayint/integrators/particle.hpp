#pragma once
// Sabella's particle (density-emitter) model, Williams & Max (1992) Sec. 2, Eq. 2, for cases with
// a single transfer function. See particle.cpp.
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"

namespace rayint {

// Empty if `tf` is a single transfer function in the particle model's sense (the three density
// functions identical, every colour function constant); otherwise the reason it is not.
std::string particle_model_mismatch(const TransferFunctions& tf);

class ParticleIntegrator final : public PieceIntegrator {
 public:
  // Throws std::invalid_argument("particle: needs a single transfer function: <reason>").
  explicit ParticleIntegrator(const TransferFunctions& tf);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  Rgb kappa_{};  // the constant particle colour per channel
};

}  // namespace rayint
