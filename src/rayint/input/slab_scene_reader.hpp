#pragma once
// A scene file whose medium is a plane-parallel slab (format in docs/multiple-scattering.md,
// "Slab scenes"; example cases/scenes/slab-disort-1b.json): the slab of slab.hpp declared the
// way scenes declare media, lights and the phase function, with detectors instead of a camera:
//   {"name", "description"?, "medium": {"type": "slab", "optical_thickness", "albedo"},
//    "phase": {"type": "isotropic" | "henyey_greenstein" (+ "g") | "lambert_sphere"},
//    "lights": [{"type": "beam", "mu0"}] or [{"type": "isotropic"}],
//    "detectors": {"mu_up"?: [...], "mu_down"?: [...]}}
// The fluxes (up at the top, diffuse and direct down at the bottom) are always reported. The
// units are those of slab.hpp: beam flux pi on a horizontal surface, isotropic intensity 1.
// Strict: unknown fields, a second light, or out-of-range numbers -> InputError naming the field.
#include <string>

#include "rayint/scattering/slab.hpp"

namespace rayint {

struct SlabScene {
  std::string name, description;
  SlabProblem problem;
};

SlabScene read_slab_scene(const std::string& path);
SlabScene parse_slab_scene(const std::string& text, const std::string& source);

}  // namespace rayint
