#include "rayint/report/cells_table.hpp"

#include <cstdio>

#include "rayint/report/text_format.hpp"

namespace rayint {

std::string cells_table(const CellsReport& r) {
  const CellsStudyOptions& o = r.options;
  std::string out = "rayint cells: seed " + std::to_string(o.seed) + ", " +
                    std::to_string(o.count) + " cells per type x " +
                    std::to_string(o.rays_per_cell) + " rays; error = max relative error of the "
                    "intensity over r, g, b, against the 50-digit polynomial reference\n\n";
  appendf(out, "%-6s %-10s %10s %10s %10s %10s %10s %10s\n", "cell", "method", "max rel", "p99 rel",
          "med rel", "segments", "us/ray", "");
  for (const auto& c : r.cells) {
    for (const auto& l : c.levels) {
      appendf(out, "%-6s %-10s %10s %10s %10s %10.1f %10.1f\n", c.type.c_str(),
              ("tets n=" + std::to_string(l.level)).c_str(), g3(l.rel.max).c_str(),
              g3(l.rel.p99).c_str(), g3(l.rel.median).c_str(), l.segments_per_ray,
              l.decompose_us_per_ray + l.exact_us_per_ray);
    }
    appendf(out, "%-6s %-10s %10s %10s %10s %10.1f %10.1f\n", c.type.c_str(), "ode",
            g3(c.ode_rel.max).c_str(), g3(c.ode_rel.p99).c_str(), g3(c.ode_rel.median).c_str(),
            c.ode_steps_per_ray, c.ode_us_per_ray);
    std::string steps;
    for (double s : c.order_steps) steps += (steps.empty() ? "" : ", ") + g3(s);
    out += "       order of the tets' error: median fit " + g3(c.order_median) + ", max fit " +
           g3(c.order_max) + ", per doubling " + steps + "; reference " +
           g3(c.reference_ms_per_ray) + " ms/ray, " + g3(c.pieces_per_ray) +
           " pieces/ray, bound <= " + g3(c.max_reference_bound_rel) + "\n";
  }
  out += "\nvoxel grids: Kuhn tetrahedra + exact against the trilinear interpolant (reference)\n";
  appendf(out, "%-8s %8s %6s %10s %10s %10s %10s %10s %12s\n", "field", "points", "rays", "max rel",
          "p99 rel", "med rel", "segments", "us/ray", "ref ms/ray");
  for (const auto& v : r.voxels) {
    appendf(out, "%-8s %8s %6d %10s %10s %10s %10.1f %10.1f %12.1f\n", v.field.c_str(),
            (std::to_string(v.points_per_axis) + "^3").c_str(), v.samples, g3(v.rel.max).c_str(),
            g3(v.rel.p99).c_str(), g3(v.rel.median).c_str(), v.segments_per_ray, v.exact_us_per_ray,
            v.reference_ms_per_ray);
  }
  out += "\n(ode: segments column = accepted steps per ray; us/ray: thread CPU time per ray, "
         "tets including the decomposition; " + std::to_string(o.threads) + " thread(s), " +
         g3(r.seconds) + " s wall)\n";
  return out;
}

}  // namespace rayint
