// Isosurface shading of flagged transfer-function intervals (see surface_shading.hpp).
#include "rayint/mesh/surface_shading.hpp"

#include <algorithm>
#include <cmath>

namespace rayint {

RayResult integrate_shaded(const RayIntegrator& method, const RayTrace& trace, const Rgb& background,
                           const SurfaceShading& shading, const GradientField& gradients) {
  Rgb intensity = background;
  Rgb transmittance{1.0, 1.0, 1.0};
  Ray piece_ray;
  piece_ray.segments.resize(1);
  std::vector<double> cuts;
  for (auto it = trace.crossings.rbegin(); it != trace.crossings.rend(); ++it) {
    const CellCrossing& c = *it;
    const double len = c.t_out - c.t_in;
    const double w = (c.s_out - c.s_in) / len;  // Eq. 13 slope
    cuts.assign({c.t_in, c.t_out});
    if (w != 0.0)
      for (const auto& iv : shading.surfaces)
        for (double s : iv) {
          const double t = c.t_in + (s - c.s_in) / w;
          if (t > c.t_in && t < c.t_out) cuts.push_back(t);
        }
    std::sort(cuts.begin(), cuts.end());
    // Pieces far -> near.
    for (std::size_t k = cuts.size() - 1; k > 0; --k) {
      const double ta = cuts[k - 1], tb = cuts[k];
      if (!(tb > ta)) continue;
      const double s_near = ta == c.t_in ? c.s_in : c.s_in + w * (ta - c.t_in);
      const double s_far = tb == c.t_out ? c.s_out : c.s_in + w * (tb - c.t_in);
      piece_ray.segments[0] = Segment{tb - ta, s_far, s_near};
      const RayResult r = method.integrate(piece_ray, nullptr);
      double factor = 1.0;
      const double s_mid = 0.5 * (s_far + s_near);
      for (const auto& iv : shading.surfaces)
        if (s_mid >= iv[0] && s_mid <= iv[1]) {
          const Vec3 p = trace.origin + 0.5 * (ta + tb) * trace.direction;
          const Vec3 g = gradients.at(static_cast<std::size_t>(c.cell), p);
          const double gn = g.norm();
          const Vec3 l = shading.headlight ? Vec3(-trace.direction) : shading.light_direction;
          factor = gn > 0.0 ? shading.ambient + shading.diffuse * std::fabs(g.dot(l) / gn) : shading.ambient;
          break;
        }
      for (int ch = 0; ch < kChannels; ++ch) {
        intensity[ch] = intensity[ch] * r.transmittance[ch] + factor * r.intensity[ch];
        transmittance[ch] *= r.transmittance[ch];
      }
    }
  }
  return RayResult{intensity, transmittance};
}

}  // namespace rayint
