#include "rayint/report/cell_render_json.hpp"

#include <sstream>

#include "rayint/report/text_format.hpp"

namespace rayint {

nlohmann::json own_cells_json(const CellTraversal& mesh) {
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [name, n] : cell_counts(mesh.mesh())) counts[name] = n;
  return {{"mode", "own"},
          {"cells", counts},
          {"points", mesh.mesh().points.size()},
          {"faces", mesh.face_count()},
          {"boundary_faces", mesh.boundary_face_count()}};
}

nlohmann::json to_json(const CellTraversalStats& s) {
  nlohmann::json j = nlohmann::json::object();
  for (const Counter<CellTraversalStats>& c : kCellTraversalCounters) j[c.name] = s.*c.member;
  return j;
}

nlohmann::json cell_mesh_render_json(const MeshCase& mc, const CellTraversal& mesh, const CellMeshRender& r,
                                     const MeshRenderComparison* compare) {
  const double busy = r.traversal_seconds + r.integration_seconds;
  nlohmann::json stats = {{"case", mc.name},
          {"source", mc.source},
          {"mesh", {{"source", mc.mesh_source}, {"cells", own_cells_json(mesh)},
                    {"repairs", zero_volume_json(mc.repairs.zero_volume, mc.repairs.zero_volume_by_type)}}},
          {"width", mc.camera->width},
          {"height", mc.camera->height},
          {"method", "own"},
          {"failed_pixels", r.failed_pixels},
          {"max_error_estimate", r.max_error_estimate},
          {"cost", {{"wall_seconds", r.wall_seconds},
                    {"threads", r.threads},
                    {"rays", r.rays},
                    {"chords", r.chords},
                    {"rays_per_second", r.wall_seconds > 0 ? static_cast<double>(r.rays) / r.wall_seconds : 0.0},
                    {"traversal_seconds", r.traversal_seconds},
                    {"integration_seconds", r.integration_seconds},
                    {"traversal_share", busy > 0 ? r.traversal_seconds / busy : 0.0},
                    {"traversal", to_json(r.traversal)}}}};
  // The method on VTK's split against the own interpolation; pixels whose own ray failed have no
  // error and are counted in non_finite.
  if (compare) stats["compare"] = comparison_json(*compare, r.error);
  return stats;
}

std::string cell_mesh_render_summary(const CellMeshRender& r, const MeshRenderComparison* compare) {
  std::string out;
  appendf(
      out,
      "rayint render: mode own: %ld rays, %ld cell chords in %.3f s on %u threads (%.3g rays/s); "
      "largest error estimate %.2g; %ld failed pixels%s\n",
      r.rays, r.chords, r.wall_seconds, r.threads,
      r.wall_seconds > 0 ? static_cast<double>(r.rays) / r.wall_seconds : 0.0, r.max_error_estimate,
      r.failed_pixels, r.failed_pixels > 0 ? " (NaN in the image, not a result)" : "");
  if (compare) out += comparison_summary(*compare, r.error, "own");
  return out;
}

namespace {
nlohmann::json rgb(const Rgb& c) { return nlohmann::json::array({c[0], c[1], c[2]}); }
}  // namespace

nlohmann::json zero_volume_json(long dropped, const std::map<std::string, long>& by_type) {
  nlohmann::json types = nlohmann::json::object();
  for (const auto& [name, n] : by_type) types[name] = n;
  return {{"dropped_zero_volume", dropped}, {"dropped_zero_volume_by_type", types}};
}

nlohmann::json own_eval_json(const std::vector<OwnCaseEvaluation>& cases, bool with_reference) {
  nlohmann::json out = {{"mode", "own"}, {"cases", nlohmann::json::array()}};
  for (const OwnCaseEvaluation& c : cases) {
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [name, n] : c.cells) counts[name] = n;
    nlohmann::json rays = nlohmann::json::array();
    for (const OwnRayEvaluation& r : c.rays) {
      nlohmann::json j = {{"chords", r.chords}};
      if (r.converged) {
        j["intensity"] = rgb(r.intensity);
        j["emission"] = rgb(r.emission);
        j["optical_depth"] = rgb(r.optical_depth);
        j["error_estimate"] = r.error_estimate;
      } else {
        j["intensity"] = nullptr;
        j["emission"] = nullptr;
        j["optical_depth"] = nullptr;
        j["error_estimate"] = nullptr;
        j["failure"] = r.failure;
      }
      if (with_reference) {
        j["reference"] = r.referenced ? rgb(r.reference_intensity) : nlohmann::json(nullptr);
        j["abs_error"] = r.referenced && r.converged ? nlohmann::json(r.abs_error) : nlohmann::json(nullptr);
        if (!r.referenced) j["reference_failure"] = r.reference_failure;
      }
      rays.push_back(j);
    }
    nlohmann::json cj = {{"name", c.name},
                         {"source", c.source},
                         {"mesh_file", c.mesh_source},
                         {"mode", "own"},
                         {"cells", counts},
                         {"mesh_repairs", zero_volume_json(c.dropped_zero_volume, c.dropped_zero_volume_by_type)},
                         {"faces", c.faces},
                         {"boundary_faces", c.boundary_faces},
                         {"rays", rays},
                         {"failed", c.failed},
                         {"seconds_per_ray", c.seconds_per_ray},
                         {"traversal", to_json(c.traversal)}};
    if (with_reference) {
      cj["reference_failed"] = c.reference_failed;
      const long ok = static_cast<long>(c.rays.size()) - c.reference_failed - c.failed;
      cj["max_abs_error"] = ok > 0 ? nlohmann::json(c.max_abs_error) : nlohmann::json(nullptr);
    }
    out["cases"].push_back(cj);
  }
  return out;
}

std::string own_eval_table(const std::vector<OwnCaseEvaluation>& cases, bool with_reference) {
  std::ostringstream s;
  for (const OwnCaseEvaluation& c : cases) {
    s << c.name << " (mode own:";
    for (const auto& [name, n] : c.cells) s << " " << n << " " << name;
    s << ")\n  ray  chords  intensity r g b" << (with_reference ? "  abs_error" : "") << "\n";
    for (std::size_t i = 0; i < c.rays.size(); ++i) {
      const OwnRayEvaluation& r = c.rays[i];
      std::string line;
      if (r.converged)
        appendf(line, "  %3zu  %6ld  %.17g %.17g %.17g", i, r.chords, r.intensity[0],
                r.intensity[1], r.intensity[2]);
      else
        appendf(line, "  %3zu  %6ld  failed: %s", i, r.chords, r.failure.c_str());
      if (with_reference) {
        if (r.referenced && r.converged)
          appendf(line, "  %.2e", r.abs_error);
        else
          line += "  -";
      }
      s << line << "\n";
    }
    s << "  failed rays: " << c.failed << "\n";
    if (c.dropped_zero_volume > 0) s << "  zero-volume cells dropped: " << c.dropped_zero_volume << "\n";
  }
  return s.str();
}

}  // namespace rayint
