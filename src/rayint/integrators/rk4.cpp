#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_rk4(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method rk4 is not implemented yet");
}

}  // namespace rayint
