#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_preintegrated(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method preintegrated is not implemented yet");
}

}  // namespace rayint
