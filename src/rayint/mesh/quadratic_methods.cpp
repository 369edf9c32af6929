// "exact" on rays with quadratic chords (see quadratic_methods.hpp).
#include "rayint/mesh/quadratic_methods.hpp"

#include <utility>

#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/model/poly_ray.hpp"

namespace rayint {
namespace {

class QuadraticExactIntegrator final : public RayIntegrator {
 public:
  QuadraticExactIntegrator(std::unique_ptr<RayIntegrator> linear, const TransferFunctions& tf)
      : linear_(std::move(linear)), tf_(tf), poly_(tf_) {}
  bool takes_quadratic_segments() const override { return true; }

 protected:
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override {
    if (!has_quadratic_segments(ray)) return linear_->integrate(ray, diag);
    const TrilinearRayResult t = poly_.integrate(to_poly_ray(ray));
    if (diag) {
      diag->count("quadratic_chords");
      diag->add_stat("pieces", static_cast<double>(t.pieces));
    }
    return RayResult{t.intensity, t.transmittance};
  }

 private:
  std::unique_ptr<RayIntegrator> linear_;
  TransferFunctions tf_;  // poly_ keeps a pointer to it
  TrilinearIntegrator poly_;
};

}  // namespace

std::unique_ptr<RayIntegrator> make_case_integrator(const MethodSpec& spec, const TransferFunctions& tf) {
  std::unique_ptr<RayIntegrator> m = make_integrator(spec, tf);
  if (spec.name != "exact") return m;
  return std::make_unique<QuadraticExactIntegrator>(std::move(m), tf);
}

}  // namespace rayint
