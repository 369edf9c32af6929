#pragma once
// The scene effect `multiple_scattering` (docs/scenes.md, docs/multiple-scattering.md): light
// scattered two or more times on its way from the scene's directional light to the eye, added to
// the `single_scattering` term (which holds order 1) so that single_scattering + shadows +
// multiple_scattering is the full solution. The term always includes the light's attenuation to
// every scattering point and the extinction along the viewing ray (orders >= 2 have no meaning
// without them).
//
// Methods (`"methods": {"multiple_scattering": "..."}`):
//   discrete_ordinates:grid=G:bins=B:points=P  Max's direction bins (6 B^2), G^3 cells (default G 32, B 3)
//   zonal:grid=G:points=P                      isotropic only (default G 12)
//   diffusion:grid=G:points=P                  P1 / diffusion on G^3 cells (default G 32;
//                                              scattering/diffusion.hpp); a solve that does not
//                                              converge is an error, never an image
//   monte_carlo:spp=N:seed=S:points=P          path tracing of orders >= 2 (default spp 64)
// points: the medium is resampled on P^3 points for every method (default 64;
// scattering/scattering_volume.hpp, volume_from_medium).
// reference(): the Monte Carlo with 1024 paths per ray (seed 1), error estimate 2 SE.
#include <memory>

#include "rayint/scene/effect.hpp"

namespace rayint {

std::unique_ptr<Effect> make_multiple_scattering_effect(const EffectContext& context);
// Its name, role, methods and parameters, and the factory above: what register_effect() takes
// (effects/standard_effects.hpp).
EffectInfo multiple_scattering_effect_info();

}  // namespace rayint
