#include <stdexcept>

#include "rayint/integrators/factories.hpp"

namespace rayint {

std::unique_ptr<RayIntegrator> make_eq5(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method eq5 is not implemented yet");
}
std::unique_ptr<RayIntegrator> make_eq6(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method eq6 is not implemented yet");
}
std::unique_ptr<RayIntegrator> make_eq7(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method eq7 is not implemented yet");
}
std::unique_ptr<RayIntegrator> make_eq8(const MethodSpec&, const TransferFunctions&) {
  throw std::invalid_argument("method eq8 is not implemented yet");
}

}  // namespace rayint
