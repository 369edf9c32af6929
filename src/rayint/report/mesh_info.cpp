// `rayint mesh info` as JSON and text (see mesh_info.hpp).
#include "rayint/report/mesh_info.hpp"

#include <cstdio>
#include <map>

#include "rayint/core/format.hpp"

namespace rayint {
namespace {

std::string cell_label(const TetMesh& m, std::size_t t) {
  return m.info.cell_ids.size() == m.tets.size() ? std::to_string(m.info.cell_ids[t]) : std::to_string(t);
}

std::pair<Vec3, Vec3> bounds(const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

// What both mesh kinds report alike: bounds, cells read by type, arrays, the scalar.
nlohmann::json file_json(const MeshFileInfo& info, const std::vector<Vec3>& points) {
  const auto [lo, hi] = bounds(points);
  nlohmann::json cells = nlohmann::json::object();
  for (const auto& [type, n] : info.cells_by_type) {
    const auto s = info.skipped_by_type.find(type);
    cells[type] = {{"read", n}, {"skipped", s == info.skipped_by_type.end() ? 0 : s->second}};
  }
  nlohmann::json arrays = nlohmann::json::array();
  for (const MeshArrayInfo& a : info.arrays)
    arrays.push_back({{"name", a.name}, {"association", a.association}, {"components", a.components},
                      {"marker", a.marker}, {"scalar", a.name == info.scalar}});
  return {{"bounds", {{"min", {lo[0], lo[1], lo[2]}}, {"max", {hi[0], hi[1], hi[2]}}}},
          {"cells_by_type", cells},
          {"skipped_cells", info.skipped_cells},
          {"ghost_cells", info.ghost_cells},
          {"merged_points", info.merged_points},
          {"skipped_node_data", info.skipped_node_data},
          {"arrays", arrays},
          {"scalar", {{"name", info.scalar}, {"association", info.scalar_association}}}};
}

// The bounds, cells and arrays lines of the text form.
std::string file_text(const MeshFileInfo& info, const std::vector<Vec3>& points) {
  const auto [lo, hi] = bounds(points);
  std::string out = "  bounds [" + format_number(lo[0]) + ", " + format_number(hi[0]) + "] x [" +
                    format_number(lo[1]) + ", " + format_number(hi[1]) + "] x [" + format_number(lo[2]) + ", " +
                    format_number(hi[2]) + "]\n";
  out += "  cells:";
  for (const auto& [type, n] : info.cells_by_type) {
    const auto s = info.skipped_by_type.find(type);
    out += " " + type + " " + std::to_string(n) + (s != info.skipped_by_type.end() ? " (skipped)" : "") + ";";
  }
  if (info.ghost_cells > 0) out += " ghost cells dropped " + std::to_string(info.ghost_cells) + ";";
  if (info.skipped_node_data > 0)
    out += " $NodeData entries for nodes gmsh did not save (tag -1 or past the last node) skipped " + std::to_string(info.skipped_node_data) + ";";
  out += "\n  arrays:";
  if (info.arrays.empty()) out += " none";
  for (const MeshArrayInfo& a : info.arrays)
    out += " \"" + a.name + "\" (" + a.association + ", " + std::to_string(a.components) +
           (a.marker ? ", marker" : "") + (a.name == info.scalar ? ", the scalar" : "") + ");";
  return out + "\n";
}

// Per kept cell type: count and corner-Jacobian orientation.
std::map<std::string, CellOrientationCounts> orientation_by_type(const CellMesh& m) {
  std::map<std::string, CellOrientationCounts> out;
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    CellOrientationCounts& o = out[mesh_cell_name(m.types[c])];
    const int s = cell_orientation(m, c);
    (s > 0 ? o.positive : s < 0 ? o.negative : o.mixed) += 1;
  }
  return out;
}

// Zero-volume cells by type (mesh/cell_mesh.hpp zero_volume_cell): the own mode drops them.
std::map<std::string, long> zero_volume_by_type(const CellMesh& m) {
  std::map<std::string, long> out;
  for (std::size_t c = 0; c < m.cell_count(); ++c)
    if (zero_volume_cell(m, c)) ++out[mesh_cell_name(m.types[c])];
  return out;
}

constexpr const char* kCellsIntegrated =
    "in each cell's own interpolation (default, \"mode\": \"own\"); --cells split integrates VTK's "
    "vtkDataSetTriangleFilter tetrahedralisation instead (an approximation of it)";

// Quadratic cells: VTK's split of them depends on point ids and positions and is not reproduced
// (cells/cell_types.hpp, quadratic_split_message): say so instead of offering it.
constexpr const char* kQuadraticCellsIntegrated =
    "in each cell's own interpolation (\"mode\": \"own\"; quadratic cells isoparametric, curved edges "
    "and faces included); --cells split refuses the quadratic cells (VTK's split of them is not reproduced)";

const char* cells_integrated(const CellMesh& m) {
  for (MeshCellType t : m.types)
    if (is_quadratic(t)) return kQuadraticCellsIntegrated;
  return kCellsIntegrated;
}

nlohmann::json cells_json(const MeshInfo& in) {
  const CellMesh& m = *in.cells;
  nlohmann::json orient = nlohmann::json::object();
  for (const auto& [type, o] : orientation_by_type(m))
    orient[type] = {{"positive", o.positive}, {"negative", o.negative}, {"mixed", o.mixed}};
  nlohmann::json j = {{"file", in.file}, {"points", m.points.size()}, {"cells", m.cell_count()}, {"tets", nullptr}};
  j.update(file_json(m.info, m.points));
  j["cell_orientation"] = orient;
  nlohmann::json zero = nlohmann::json::object();
  long zero_total = 0;
  for (const auto& [type, n] : zero_volume_by_type(m)) zero[type] = n, zero_total += n;
  j["zero_volume_cells"] = {{"total", zero_total}, {"by_type", zero},
                            {"own_mode", "dropped and counted (--strict-mesh: refused)"}};
  j["integrated"] = cells_integrated(m);
  j["check"] = "not run (--check covers tetrahedral meshes)";
  if (m.structured) j["structured_dimensions"] = {(*m.structured)[0], (*m.structured)[1], (*m.structured)[2]};
  return j;
}

std::string cells_text(const MeshInfo& in) {
  const CellMesh& m = *in.cells;
  std::string out = in.file + "\n";
  out += "  points " + std::to_string(m.points.size()) + ", volume cells " + std::to_string(m.cell_count());
  if (m.structured)
    out += " (structured " + std::to_string((*m.structured)[0]) + " x " + std::to_string((*m.structured)[1]) + " x " +
           std::to_string((*m.structured)[2]) + " points)";
  out += "\n" + file_text(m.info, m.points);
  out += "  orientation (corner Jacobians):";
  for (const auto& [type, o] : orientation_by_type(m))
    out += " " + type + " positive " + std::to_string(o.positive) + ", negative " + std::to_string(o.negative) +
           ", mixed " + std::to_string(o.mixed) + ";";
  long zero_total = 0;
  std::string zero_types;
  for (const auto& [type, n] : zero_volume_by_type(m)) zero_total += n, zero_types += " " + type + " " + std::to_string(n) + ";";
  out += "\n  zero volume: " + std::to_string(zero_total) + (zero_total > 0 ? " (" + zero_types.substr(1) + " dropped in the own mode)" : "");
  out += std::string("\n  integrated: ") + cells_integrated(m) + "\n";
  return out;
}

}  // namespace

nlohmann::json to_json(const MeshInfo& in) {
  if (in.cells != nullptr) return cells_json(in);
  const TetMesh& m = *in.mesh;
  nlohmann::json j = {{"file", in.file}, {"points", m.points.size()}, {"tets", m.tets.size()}};
  j.update(file_json(m.info, m.points));
  j["orientation"] = {{"positive", in.orientation.positive}, {"inverted", in.orientation.inverted},
                      {"zero_volume", in.orientation.zero_volume}, {"slivers", in.orientation.slivers}};
  if (in.tet10) {
    const Tet10EdgeCheck& q = *in.tet10;
    j["quadratic_tets"] = {{"tets", q.quadratic_tets},
                           {"edges", q.straight() ? "straight" : "curved"},
                           {"worst_edge_offset", q.worst_offset},
                           {"worst_cell", cell_label(m, q.worst_tet)},
                           {"tolerance", kStraightEdgeTolerance},
                           {"integrated", q.straight() ? "quadratic interpolation, exact along each chord"
                                                       : "isoparametric (curved edges): in the cells' own interpolation, "
                                                         "mesh/cell_traversal.hpp"}};
  } else {
    j["quadratic_tets"] = {{"tets", 0}};
  }
  if (in.checked) {
    j["check"] = {{"overlap", in.overlap.has_value()}, {"seconds", in.check_seconds}};
    if (in.overlap)
      j["check"]["overlapping_cells"] = {cell_label(m, in.overlap->first), cell_label(m, in.overlap->second)};
  } else {
    j["check"] = "not run (--check)";
  }
  return j;
}

std::string to_text(const MeshInfo& in) {
  if (in.cells != nullptr) return cells_text(in);
  const TetMesh& m = *in.mesh;
  std::string out = in.file + "\n";
  out += "  points " + std::to_string(m.points.size()) + ", tetrahedra " + std::to_string(m.tets.size()) + "\n";
  out += file_text(m.info, m.points);
  out += "  orientation: positive " + std::to_string(in.orientation.positive) + ", inverted " +
         std::to_string(in.orientation.inverted) + ", zero volume " + std::to_string(in.orientation.zero_volume) +
         ", slivers " + std::to_string(in.orientation.slivers) + "\n";
  if (in.tet10) {
    const Tet10EdgeCheck& q = *in.tet10;
    out += "  quadratic tetrahedra " + std::to_string(q.quadratic_tets) + ": edges " +
           (q.straight() ? "straight" : "curved") + " (largest mid-edge offset " + format_number(q.worst_offset) +
           " of the edge length, cell " + cell_label(m, q.worst_tet) + "; straight within " +
           format_number(kStraightEdgeTolerance) + ")" +
           (q.straight() ? ", integrated with their quadratic interpolation\n"
                         : ", integrated in their own isoparametric interpolation (curved cells)\n");
  }
  if (in.checked) {
    char t[64];
    std::snprintf(t, sizeof t, " (%.3f s)", in.check_seconds);
    out += in.overlap ? "  check: cells " + cell_label(m, in.overlap->first) + " and " + cell_label(m, in.overlap->second) +
                            " overlap" + t + "\n"
                      : std::string("  check: no overlapping tetrahedra") + t + "\n";
  }
  return out;
}

}  // namespace rayint
