// Validation of a plane-parallel slab problem; see slab.hpp.
#include "rayint/scattering/slab.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rayint {

void validate(const SlabProblem& p) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("slab: " + what); };
  if (!(std::isfinite(p.tau) && p.tau > 0)) bad("tau must be finite and > 0");
  if (!(p.albedo >= 0 && p.albedo <= 1)) bad("albedo must be in [0, 1]");
  if (p.source == SlabSource::beam && !(p.mu0 > 0 && p.mu0 <= 1)) bad("mu0 must be in (0, 1]");
  for (double m : p.mu_up)
    if (!(m > 0 && m <= 1)) bad("detector cosines mu must be in (0, 1]");
  for (double m : p.mu_down)
    if (!(m > 0 && m <= 1)) bad("detector cosines mu must be in (0, 1]");
}

}  // namespace rayint
