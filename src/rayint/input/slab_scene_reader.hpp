#pragma once
// A scene file whose medium is a plane-parallel slab (format in docs/multiple-scattering.md,
// "Slab scenes"; example cases/scenes/slab-disort-1b.json): the slab of slab.hpp declared the
// way scenes declare media, lights and the phase function, with detectors instead of a camera:
//   {"name", "description"?, "medium": {"type": "slab", "optical_thickness", "albedo"},
//    "phase": {"type": "isotropic" | "henyey_greenstein" (+ "g") | "lambert_sphere"
//              | "legendre" (+ "coefficients": [1, chi_1, ...])
//              | "tabulated" (+ "points": [[cos_theta, p], ...] from -1 to 1, linear between)},
//    "lights": [{"type": "beam", "mu0"}] or [{"type": "isotropic"}],
//    "detectors": {"mu_up"?: [...], "mu_down"?: [...]},
//    "ground"?: {"type": "lambertian", "albedo": A}}   (absent: black ground)
// The fluxes (up at the top, diffuse and direct down at the bottom) are always reported. The
// units are those of slab.hpp: beam flux pi on a horizontal surface, isotropic intensity 1.
// Strict: unknown fields, a second light, or out-of-range numbers -> InputError naming the field.
#include <string>

#include <vector>

#include "rayint/scattering/pn.hpp"
#include "rayint/scattering/slab.hpp"

namespace rayint {

// A "legendre" or "tabulated" phase function is known only by its Legendre coefficients: only
// P_N solves it (PnOptions::legendre), and problem.phase is then isotropic, a placeholder no other
// solver may use (rayint slab refuses them). A table's coefficients are computed to
// kSlabTableOrder (legendre_from_table, exact for the linear interpolant); P_N truncates them to
// its order, and its single-scattering term sums all of them.
inline constexpr int kSlabTableOrder = 255;

struct SlabScene {
  std::string name, description;
  SlabProblem problem;
  std::vector<double> legendre;  // non-empty: the phase function as Legendre coefficients
  std::string phase_name;        // isotropic, henyey_greenstein, lambert_sphere, legendre, tabulated
};

SlabScene read_slab_scene(const std::string& path);
SlabScene parse_slab_scene(const std::string& text, const std::string& source);

}  // namespace rayint
