#pragma once
// Isosurface shading inside a volume rendering (Williams & Max 1992, end of Sec. 3.3): only the
// transfer-function intervals flagged as surfaces (a tall narrow pulse in the density) are
// shaded; the rest of the volume is not.
//
// Model: on the parts of a ray whose scalar lies in a flagged interval [lo, hi], the emitted
// light (chromaticity kappa) is multiplied by ambient + diffuse * |n . l|, with n the unit
// gradient (Sec. 3.2, mesh/gradients.hpp) and l the unit direction toward the light (default:
// a headlight, l = -ray direction). Each cell crossing is cut at lo and hi with Eq. 13
// (t = t_in + (s - v) / w), every piece is integrated by the given method as a one-segment ray,
// and the pieces are composited far -> near: I <- I T + factor E. With the per-cell gradient the
// factor is constant on each piece, so with `exact` the shaded image is exact for this model;
// with the interpolated gradients the factor is taken at each piece's midpoint (an
// approximation of a factor that varies along the piece).
// Off by default; the case-file switch is "shading" (cases/README.md).
#include <array>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/gradients.hpp"
#include "rayint/mesh/tet_traversal.hpp"

namespace rayint {

struct SurfaceShading {
  bool enabled = false;
  std::vector<std::array<double, 2>> surfaces;  // flagged scalar intervals [lo, hi], lo < hi
  GradientMode gradient = GradientMode::cell;
  bool headlight = true;                        // l = -ray direction
  Vec3 light_direction = Vec3::UnitZ();         // toward the light, unit (when !headlight)
  double ambient = 0.2;
  double diffuse = 0.8;
};

RayResult integrate_shaded(const RayIntegrator& method, const RayTrace& trace, const Rgb& background,
                           const SurfaceShading& shading, const GradientField& gradients);

}  // namespace rayint
