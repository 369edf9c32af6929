#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_psi_table(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method psi_table is not implemented yet");
}

}  // namespace rayint
