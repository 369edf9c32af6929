#pragma once
// Factories of the methods other than exact/paper; each is defined in the file named after it
// (the cell rules' here).
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <string>

#include "rayint/integrators/cell_approximations.hpp"
#include "rayint/integrators/integrator.hpp"

namespace rayint {

// For the factories: the position of spec.text(key) in `values`: choice_of(spec, "at", {"mid",
// "near"}) is 0 or 1; any other value throws std::invalid_argument "method NAME: at must be mid or
// near, got 'X'".
std::size_t choice_of(const MethodSpec& spec, const std::string& key, std::initializer_list<const char*> values);

std::unique_ptr<RayIntegrator> make_ode(const MethodSpec&, const TransferFunctions&);        // ode.cpp
std::unique_ptr<RayIntegrator> make_rk4(const MethodSpec&, const TransferFunctions&);        // rk4.cpp
std::unique_ptr<RayIntegrator> make_riemann(const MethodSpec&, const TransferFunctions&);    // riemann.cpp
// eq5, eq6, eq7, eq8: the one CellIntegrator (cell_approximations.hpp), its rule the method's.
template <CellRule rule>
std::unique_ptr<RayIntegrator> make_cell_rule(const MethodSpec&, const TransferFunctions& tf) {
  return std::make_unique<CellIntegrator>(tf, rule);
}
std::unique_ptr<RayIntegrator> make_particle(const MethodSpec&, const TransferFunctions&);   // particle.cpp
std::unique_ptr<RayIntegrator> make_preintegrated(const MethodSpec&, const TransferFunctions&);  // preintegrated.cpp
std::unique_ptr<RayIntegrator> make_psi_table(const MethodSpec&, const TransferFunctions&);  // psi_table.cpp
std::unique_ptr<RayIntegrator> make_nerf(const MethodSpec&, const TransferFunctions&);       // nerf.cpp
std::unique_ptr<RayIntegrator> make_pl_nerf(const MethodSpec&, const TransferFunctions&);    // nerf.cpp

}  // namespace rayint
