#include "rayint/report/mesh_render_json.hpp"

#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/report/evaluation_json.hpp"
#include "rayint/report/text_format.hpp"

namespace rayint {

nlohmann::json to_json(const MeshRenderCost& c) {
  const double busy = c.traversal_seconds + c.integration_seconds;
  const TraversalStats& t = c.traversal;
  return {{"wall_seconds", c.wall_seconds},
          {"threads", c.threads},
          {"rays", c.rays},
          {"segments", c.segments},
          {"pieces", c.pieces},
          {"rays_per_second", c.wall_seconds > 0 ? static_cast<double>(c.rays) / c.wall_seconds : 0.0},
          {"pieces_per_second", c.wall_seconds > 0 ? static_cast<double>(c.pieces) / c.wall_seconds : 0.0},
          {"traversal_seconds", c.traversal_seconds},
          {"integration_seconds", c.integration_seconds},
          {"traversal_share", busy > 0 ? c.traversal_seconds / busy : 0.0},
          {"integration_share", busy > 0 ? c.integration_seconds / busy : 0.0},
          {"traversal", {{"face_steps", t.face_steps}, {"zero_length_steps", t.zero_length_steps},
                         {"star_searches", t.star_searches}, {"first_hit_queries", t.first_hit_queries},
                         {"budget_exhausted", t.budget_exhausted}}}};
}

nlohmann::json mesh_render_json(const MeshCase& mc, const TetTraversal& mesh, const MeshRender& r,
                                const MeshRenderComparison* compare) {
  nlohmann::json stats = {{"case", mc.name},
                          {"source", mc.source},
                          {"mesh", {{"source", mc.mesh_source}, {"points", mesh.mesh().points.size()},
                                    {"tets", mesh.mesh().tets.size()},
                                    {"quadratic_tets", check_tet10_edges(mesh.mesh()).quadratic_tets},
                                    {"boundary_faces", mesh.boundary_face_count()},
                                    {"repairs", to_json(mc.repairs)}}},
                          {"width", mc.camera->width},
                          {"height", mc.camera->height},
                          // Quadratic tetrahedra: "exact" along each chord's quadratic (mesh/quadratic_tets.hpp).
                          {"method", mesh.quadratic() ? "exact (quadratic tetrahedra)" : "exact"},
                          {"shading", mc.shading.enabled},
                          {"cost", to_json(r.cost)}};
  if (compare) stats["compare"] = comparison_json(*compare, r.error);
  return stats;
}

std::string mesh_render_summary(const MeshRender& r, const MeshRenderComparison* compare) {
  const MeshRenderCost& c = r.cost;
  const double busy = c.traversal_seconds + c.integration_seconds;
  std::string out;
  appendf(out,
          "rayint render: %ld rays in %.3f s on %u threads: %.3g rays/s, %.3g pieces/s, "
          "traversal %.0f%% / integration %.0f%%\n",
          c.rays, c.wall_seconds, c.threads, static_cast<double>(c.rays) / c.wall_seconds,
          static_cast<double>(c.pieces) / c.wall_seconds,
          busy > 0 ? 100 * c.traversal_seconds / busy : 0.0,
          busy > 0 ? 100 * c.integration_seconds / busy : 0.0);
  if (compare) out += comparison_summary(*compare, r.error, "exact");
  return out;
}

nlohmann::json comparison_json(const MeshRenderComparison& compare, const ErrorSummary& e) {
  return {{"method", compare.label},
          {"heat_map", compare.heat_map},
          {"pixels", e.pixels},
          {"max_rel_error", e.max_rel},
          {"mean_rel_error", e.mean_rel},
          {"median_rel_error", e.median_rel},
          {"p99_rel_error", e.p99_rel},
          {"max_abs_error", e.max_abs},
          {"non_finite", e.non_finite}};
}

std::string comparison_summary(const MeshRenderComparison& compare, const ErrorSummary& e, const char* against) {
  std::string line;
  appendf(line, "rayint render: %s vs %s: max rel %.3g, median %.3g, p99 %.3g -> %s\n",
          compare.label.c_str(), against, e.max_rel, e.median_rel, e.p99_rel,
          compare.heat_map.c_str());
  return line;
}

}  // namespace rayint
