#pragma once
// The terms that reflect external light (Max 1995, Sec. 5-6), each attenuated along the viewing
// ray when `absorption` is named and shadowed when `shadows` is:
//   single_scattering: S(p) = sigma_s(p) sum_L p(w_L . w_eye) E_L(p) T_L(p)   (Sec. 5, 6)
//     with w_L the light's propagation direction, w_eye = -view direction (toward the eye), p the
//     phase function, E_L the unshadowed irradiance and T_L the shadowing (scene/shadowing.hpp);
//   shading: Max's gradient-strength surface shading (scene.hpp ShadingParams), times E_L T_L.
// Method: riemann:n (media/riemann_march.hpp) with the scene's Shadowing; reference:
// scene/term_references.hpp, nested over the light depth when shadowed.
#include <memory>

#include "rayint/scene/effect.hpp"

namespace rayint {

std::unique_ptr<Effect> make_single_scattering_effect(const EffectContext& context);
std::unique_ptr<Effect> make_shading_effect(const EffectContext& context);

}  // namespace rayint
