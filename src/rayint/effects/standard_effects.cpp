// Registration of the effects outside scene/; see standard_effects.hpp.
#include "rayint/effects/standard_effects.hpp"

#include "rayint/effects/multiple_scattering_effect.hpp"

namespace rayint {

void register_standard_effects() { register_effect(multiple_scattering_effect_info()); }

}  // namespace rayint
