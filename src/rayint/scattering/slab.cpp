// Validation of a plane-parallel slab problem; see slab.hpp.
#include "rayint/scattering/slab.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/core/math.hpp"

namespace rayint {

void validate(const SlabProblem& p) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("slab: " + what); };
  if (!(std::isfinite(p.tau) && p.tau > 0)) bad("tau must be finite and > 0");
  if (!(p.albedo >= 0 && p.albedo <= 1)) bad("albedo must be in [0, 1]");
  if (!(p.ground_albedo >= 0 && p.ground_albedo <= 1)) bad("ground_albedo must be in [0, 1]");
  if (p.source == SlabSource::beam && !(p.mu0 > 0 && p.mu0 <= 1)) bad("mu0 must be in (0, 1]");
  for (double m : p.mu_up)
    if (!(m > 0 && m <= 1)) bad("detector cosines mu must be in (0, 1]");
  for (double m : p.mu_down)
    if (!(m > 0 && m <= 1)) bad("detector cosines mu must be in (0, 1]");
}

SlabValues add_lambertian_ground(const SlabProblem& p, const SlabValues& black, const SlabValues& iso) {
  const double A = p.ground_albedo;
  const double down = black.diffuse_down_bottom + black.direct_down_bottom;
  const double s = iso.flux_up_top / kPi, t = iso.diffuse_down_bottom / kPi;
  const double Fg = A * down / (1 - A * s);  // s < 1 for tau > 0, so 1 - A s > 0
  SlabValues v = black;
  v.flux_up_top += Fg * t;
  v.diffuse_down_bottom += Fg * s;
  for (std::size_t i = 0; i < v.intensity_up_top.size(); ++i)
    v.intensity_up_top[i] += Fg / kPi * iso.intensity_down_bottom.at(i);
  for (std::size_t i = 0; i < v.intensity_down_bottom.size(); ++i)
    v.intensity_down_bottom[i] += Fg / kPi * iso.intensity_up_top.at(i);
  return v;
}

}  // namespace rayint
