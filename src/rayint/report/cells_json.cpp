// JSON of the cells study: options, one table per cell type (error per subdivision level,
// fitted orders, ODE, reference cost) and the voxel-grid table.
#include "rayint/report/cells_json.hpp"

#include <cmath>

#include "rayint/report/json_number.hpp"
#include "rayint/report/stress_json.hpp"  // to_json(ErrorStats)

namespace rayint {

namespace {
using json = nlohmann::ordered_json;
}  // namespace

nlohmann::ordered_json to_json(const CellsReport& r) {
  json j;
  const CellsStudyOptions& o = r.options;
  j["study"] = "decomposition of higher-order cells into linear tetrahedra (exact) and voxel "
               "grids (Kuhn tetrahedra, exact) against the 50-digit polynomial reference";
  j["options"] = json{{"count", o.count},           {"seed", o.seed},
                      {"rays_per_cell", o.rays_per_cell}, {"levels", o.levels},
                      {"ode_rtol", o.ode_rtol},     {"voxel_random_points", o.voxel_random_points},
                      {"voxel_sizes", o.voxel_sizes}, {"voxel_rays", o.voxel_rays},
                      {"threads", o.threads}};
  j["error"] = "per ray: largest relative error of the intensity over r, g, b";
  json cells = json::array();
  for (const auto& c : r.cells) {
    json t;
    t["type"] = c.type;
    t["rays"] = c.samples;
    json levels = json::array();
    for (const auto& l : c.levels)
      levels.push_back(json{{"level", l.level},
                            {"rel_error", to_json(l.rel)},
                            {"segments_per_ray", number_or_null<json>(l.segments_per_ray)},
                            {"decompose_us_per_ray", number_or_null<json>(l.decompose_us_per_ray)},
                            {"exact_us_per_ray", number_or_null<json>(l.exact_us_per_ray)}});
    t["levels"] = levels;
    json steps = json::array();
    for (double s : c.order_steps) steps.push_back(number_or_null<json>(s));
    t["order"] = json{{"median_fit", number_or_null<json>(c.order_median)},
                      {"max_fit", number_or_null<json>(c.order_max)},
                      {"median_per_doubling", steps}};
    t["ode"] = json{{"rtol", o.ode_rtol},
                    {"rel_error", to_json(c.ode_rel)},
                    {"us_per_ray", number_or_null<json>(c.ode_us_per_ray)},
                    {"steps_per_ray", number_or_null<json>(c.ode_steps_per_ray)}};
    t["reference"] = json{{"ms_per_ray", number_or_null<json>(c.reference_ms_per_ray)},
                          {"pieces_per_ray", number_or_null<json>(c.pieces_per_ray)},
                          {"max_rel_error_bound", number_or_null<json>(c.max_reference_bound_rel)}};
    cells.push_back(t);
  }
  j["cells"] = cells;
  json voxels = json::array();
  for (const auto& v : r.voxels)
    voxels.push_back(json{{"field", v.field},
                          {"points_per_axis", v.points_per_axis},
                          {"rays", v.samples},
                          {"rel_error", to_json(v.rel)},
                          {"segments_per_ray", number_or_null<json>(v.segments_per_ray)},
                          {"exact_us_per_ray", number_or_null<json>(v.exact_us_per_ray)},
                          {"reference_ms_per_ray", number_or_null<json>(v.reference_ms_per_ray)}});
  j["voxels"] = voxels;
  j["seconds"] = number_or_null<json>(r.seconds);
  return j;
}

}  // namespace rayint
