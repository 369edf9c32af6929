#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_riemann(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method riemann is not implemented yet");
}

}  // namespace rayint
