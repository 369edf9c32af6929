#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_ode(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method ode is not implemented yet");
}

}  // namespace rayint
