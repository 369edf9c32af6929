#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_particle(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method particle is not implemented yet");
}

}  // namespace rayint
