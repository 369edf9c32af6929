// Mesh case reader (see mesh_case_reader.hpp; format in cases/README.md).
#include "rayint/input/mesh_case_reader.hpp"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/cells/cell_types.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/mesh_check.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/input/gmsh_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/tetgen_reader.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"

namespace rayint {
namespace {

// The built-in readers, chosen by extension; each takes the array to integrate and whether a cell
// field becomes averaged point data ("cell_data": "point_average").
using BuiltinReader = TetMesh (*)(const std::string& path, const ScalarChoice& scalar);
TetMesh read_tetgen_mesh(const std::string& path, const ScalarChoice& scalar) {
  return read_tetgen(path, scalar.name);  // TetGen point attributes are point data only
}
// Structured grids hold hexahedra (.vts) or voxels (.vtr, .vti): the tetrahedral path refuses them
// the way it refuses any non-tetrahedral cell (unsupported_cell_message: use --cells split).
template <CellMesh (*Read)(const std::string&, const ScalarChoice&)>
TetMesh read_structured_as_tets(const std::string& path, const ScalarChoice& scalar) {
  CellMesh m = Read(path, scalar);
  for (std::size_t c = 0; c < m.cell_count(); ++c)
    if (m.types[c] != MeshCellType::tetra)
      throw InputError(path + ": cells[" + std::to_string(c) + "]: " + unsupported_cell_message(static_cast<int>(m.types[c])));
  return take_tets(std::move(m));
}

const std::map<std::string, BuiltinReader>& builtin_mesh_readers() {
  static const std::map<std::string, BuiltinReader> readers = {
      {".vtk", &read_vtk_legacy},   // VTK legacy (vtk_legacy_reader.hpp)
      {".ele", &read_tetgen_mesh},  // TetGen .ele + .node (tetgen_reader.hpp)
      {".msh", &read_gmsh},         // gmsh MSH 2.2 / 4.1 (gmsh_reader.hpp)
      {".vtu", &read_vtu},          // VTK XML, without VTK (vtk_xml_reader.hpp)
      {".pvtu", &read_pvtu},        // its parallel pieces (vtk_xml_reader.hpp)
      {".vts", &read_structured_as_tets<&read_vts>},  // structured grids: refused without --cells split
      {".vtr", &read_structured_as_tets<&read_vtr>},
      {".pvts", &read_structured_as_tets<&read_pvts>},  // parallel structured grids: their pieces joined
      {".pvtr", &read_structured_as_tets<&read_pvtr>},
      {".vti", &read_structured_as_tets<&read_vti_cells>},  // an image as its voxels (cell data)
  };
  return readers;
}

// Readers registered by optional areas (register_mesh_reader); they replace a built-in one.
std::map<std::string, MeshFileReader>& extra_mesh_readers() {
  static std::map<std::string, MeshFileReader> readers;
  return readers;
}

std::string known_mesh_extensions() {
  std::string out;
  for (const auto& [ext, read] : builtin_mesh_readers()) out += (out.empty() ? "" : ", ") + ext;
  for (const auto& [ext, read] : extra_mesh_readers())
    if (builtin_mesh_readers().count(ext) == 0) out += ", " + ext;
  return out;
}

using nlohmann::json;
using json_source::index_path;
using json_source::member_path;

TetMesh inline_mesh(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  s.check_fields(j, path, {"points", "scalars", "tets"});
  TetMesh m;
  const std::string pp = member_path(path, "points"), sp = member_path(path, "scalars"),
                    tp = member_path(path, "tets");
  const json& pts = s.required(j, path, "points");
  s.non_empty_array(pts, pp, "");
  m.points.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) m.points.push_back(s.vec3(pts[i], index_path(pp, i)));
  const json& sc = s.required(j, path, "scalars");
  s.non_empty_array(sc, sp, "");
  m.scalars.reserve(sc.size());
  for (std::size_t i = 0; i < sc.size(); ++i) m.scalars.push_back(s.finite_number(sc[i], index_path(sp, i)));
  const json& tets = s.required(j, path, "tets");
  s.non_empty_array(tets, tp, "");
  m.tets.reserve(tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const std::string ti = index_path(tp, i);
    s.array_of_size(tets[i], ti, 4, "[i, j, k, l] point indices");
    std::array<std::int32_t, 4> t{};
    for (std::size_t k = 0; k < 4; ++k)
      t[k] = static_cast<std::int32_t>(s.integer(tets[i][k], index_path(ti, k), INT32_MIN, INT32_MAX));
    m.tets.push_back(t);
  }
  validate_tet_mesh_structure(m, s.source(), MeshFieldNames{pp, sp, tp});
  return m;
}

SurfaceShading shading(const JsonSchema& s, const json& j, const std::string& path) {
  s.require_object(j, path);
  s.check_fields(j, path, {"enabled", "surfaces", "gradient", "light_direction", "ambient", "diffuse"});
  SurfaceShading sh;
  sh.enabled = true;
  if (const json* e = s.optional(j, "enabled")) sh.enabled = s.boolean(*e, member_path(path, "enabled"));
  const std::string sp = member_path(path, "surfaces");
  const json& surf = s.required(j, path, "surfaces");
  s.non_empty_array(surf, sp, "");
  for (std::size_t i = 0; i < surf.size(); ++i) {
    const std::string ip = index_path(sp, i);
    s.array_of_size(surf[i], ip, 2, "a [lo, hi] scalar interval");
    const double lo = s.finite_number(surf[i][0], index_path(ip, 0));
    const double hi = s.finite_number(surf[i][1], index_path(ip, 1));
    if (!(lo < hi)) s.fail(ip, "need lo < hi");
    sh.surfaces.push_back({lo, hi});
  }
  if (const json* g = s.optional(j, "gradient")) {
    const std::string gp = member_path(path, "gradient");
    try {
      sh.gradient = parse_gradient_mode(s.string_value(*g, gp));
    } catch (const std::invalid_argument& e) {
      s.fail(gp, e.what());
    }
  }
  if (const json* l = s.optional(j, "light_direction")) {
    sh.headlight = false;
    sh.light_direction = s.direction(*l, member_path(path, "light_direction"));
  }
  if (const json* a = s.optional(j, "ambient")) sh.ambient = s.non_negative(*a, member_path(path, "ambient"));
  if (const json* d = s.optional(j, "diffuse")) sh.diffuse = s.non_negative(*d, member_path(path, "diffuse"));
  return sh;
}

// The names a format gives its tets, for strict refusals ("mesh.tets[3]", "CELLS[3]", ...).
MeshFieldNames file_field_names(const std::string& extension) {
  if (extension == ".vtk") return {"POINTS", "POINT_DATA", "CELLS"};
  if (extension == ".ele") return {"node", "node attribute", "ele"};  // tetgen_reader.hpp
  if (extension == ".msh") return {"$Nodes", "$NodeData", "$Elements"};
  if (extension == ".pvtu") return {"pieces/Points", "pieces/PointData", "pieces/Cells"};
  return {"Points", "PointData", "Cells"};
}

}  // namespace

TetMesh read_mesh_file(const std::string& path, const ScalarChoice& scalar) {
  // One reader per format, chosen by extension (other mesh formats plug in here).
  const std::string ext = std::filesystem::path(path).extension().string();
  const auto extra = extra_mesh_readers().find(ext);
  const auto builtin = builtin_mesh_readers().find(ext);
  if (extra != extra_mesh_readers().end()) {
    TetMesh mesh = extra->second(path, scalar.name);
    if (scalar.cell_to_point && !mesh.cell_scalars.empty()) {
      mesh.scalars = cell_to_point_average(mesh);
      mesh.cell_scalars.clear();
    }
    return mesh;
  }
  if (builtin != builtin_mesh_readers().end()) return builtin->second(path, scalar);
  throw InputError(path + ": (file): unsupported mesh format \"" + ext + "\" (read: " + known_mesh_extensions() + ")");
}

namespace {
using CellReader = CellMesh (*)(const std::string&, const ScalarChoice&);
const std::map<std::string, CellReader>& cell_readers() {
  static const std::map<std::string, CellReader> readers = {
      {".vtk", &read_vtk_legacy_cells}, {".vtu", &read_vtu_cells}, {".pvtu", &read_pvtu_cells},
      {".msh", &read_gmsh_cells},       {".vts", &read_vts},       {".vtr", &read_vtr},
      {".vti", &read_vti_cells},        {".pvts", &read_pvts},     {".pvtr", &read_pvtr},
  };
  return readers;
}
// Whether files ending in `ext` are read by a built-in cell reader (not replaced by a registered one).
bool has_cell_reader(const std::string& ext) {
  return cell_readers().count(ext) > 0 && extra_mesh_readers().count(ext) == 0;
}
}  // namespace

CellMesh read_cell_mesh_file(const std::string& path, const ScalarChoice& scalar) {
  const auto& readers = cell_readers();
  const std::string ext = std::filesystem::path(path).extension().string();
  const auto it = readers.find(ext);
  if (it != readers.end() && extra_mesh_readers().count(ext) == 0) return it->second(path, scalar);
  // Formats of tetrahedra only (TetGen, registered readers): their TetMesh as cells.
  // Quadratic tetrahedra become quadratic tetra cells, as the cell readers give them.
  return cell_mesh_of(read_mesh_file(path, scalar));
}

bool is_mesh_case(const json& root) {
  return root.is_object() && (root.contains("mesh") || root.contains("mesh_file"));
}

MeshCase parse_mesh_case(const json& root, const std::string& source, const MeshReadOptions& options) {
  const JsonSchema s(source);
  const std::string path;
  s.require_object(root, path);
  s.check_fields(root, path, {"name", "description", "transfer_function", "mesh", "mesh_file",
                              "scalar_field", "cell_data", "rays", "camera", "background", "shading"});
  MeshCase mc;
  mc.source = source;
  mc.name = s.non_empty_string(s.required(root, path, "name"), "name");
  if (const json* d = s.optional(root, "description")) mc.description = s.string_value(*d, "description");
  mc.transfer = s.transfer_functions(s.required(root, path, "transfer_function"), "transfer_function");
  const json* inline_m = s.optional(root, "mesh");
  const json* file = s.optional(root, "mesh_file");
  if ((inline_m != nullptr) == (file != nullptr))
    s.fail(path, "give exactly one of \"mesh\" (inline) or \"mesh_file\" (a .vtk file)");
  const json* scalar_field = s.optional(root, "scalar_field");
  MeshFieldNames names{"mesh.points", "mesh.scalars", "mesh.tets"};
  if (inline_m) {
    if (scalar_field) s.fail("scalar_field", "only with \"mesh_file\"");
    if (s.optional(root, "cell_data")) s.fail("cell_data", "only with \"mesh_file\"");
    mc.mesh = inline_mesh(s, *inline_m, "mesh");
    mc.mesh_source = source;
  } else {
    const std::string rel = s.non_empty_string(*file, "mesh_file");
    namespace fs = std::filesystem;
    const fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : fs::path(source).parent_path() / rel;
    mc.mesh_source = p.string();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) s.fail("mesh_file", "no such file: " + mc.mesh_source);
    ScalarChoice scalar;
    if (scalar_field) scalar.name = s.non_empty_string(*scalar_field, "scalar_field");
    if (const json* cd = s.optional(root, "cell_data")) {
      const std::string how = s.non_empty_string(*cd, "cell_data");
      if (how == "point_average") scalar.cell_to_point = true;
      else if (how != "constant") s.fail("cell_data", "expected \"constant\" (default) or \"point_average\", got " + field::quoted(how));
    }
    const std::string ext = p.extension().string();
    if (extra_mesh_readers().count(ext) == 0 && builtin_mesh_readers().count(ext) == 0)
      s.fail("mesh_file", "unsupported mesh format \"" + ext + "\" (read: " + known_mesh_extensions() + ")");
    if (options.split_cells) {
      CellSplitCounts counts;
      CellMesh cells = read_cell_mesh_file(mc.mesh_source, scalar);
      for (std::size_t c = 0; c < cells.cell_count(); ++c)  // VTK's split of them is not reproduced
        if (is_quadratic(cells.types[c]))
          throw InputError(mc.mesh_source + ": cells[" +
                           std::to_string(c < cells.info.cell_ids.size() ? cells.info.cell_ids[c] : static_cast<long long>(c)) +
                           "]: " + quadratic_split_message(static_cast<int>(cells.types[c])));
      mc.mesh = split_cells(cells, &counts);
      mc.split = counts;
    } else {
      try {
        mc.mesh = read_mesh_file(mc.mesh_source, scalar);
      } catch (const InputError&) {
        // The tetrahedral readers refuse any other volume cell. A file that the cell readers take
        // and that holds such cells is integrated in their own interpolation ("mode": "own"); for
        // any other file the tetrahedral reader's message stands. Tetrahedra-only files never
        // come here: their path is unchanged.
        if (!has_cell_reader(ext)) throw;
        CellMesh cells = read_cell_mesh_file(mc.mesh_source, scalar);
        if (cells.only_tets()) throw;
        mc.cells = std::move(cells);
      }
      // Quadratic tetrahedra with curved edges: their isoparametric interpolation on the
      // own-cells path (mesh/cell_traversal.hpp); straight-edged ones stay on the tetrahedral
      // path (mesh/quadratic_tets.hpp), exact along each chord's quadratic.
      if (!mc.cells && !mc.mesh.edge_nodes.empty() && !check_tet10_edges(mc.mesh).straight()) {
        mc.cells = cell_mesh_of(std::move(mc.mesh));
        mc.mesh = TetMesh{};
      }
    }
    names = file_field_names(p.extension().string());
  }
  if (mc.cells) {
    // Own interpolation: no tetrahedra to repair; zero-volume cells refused (strict) or dropped
    // and counted (mesh/cell_mesh.hpp), like degenerate tetrahedra; the traversal refuses a face
    // shared by more than two cells when it is built.
    if (options.strict) {
      refuse_zero_volume_cells(*mc.cells, mc.mesh_source);
    } else {
      for (const auto& [type, n] : drop_zero_volume_cells(*mc.cells, mc.mesh_source)) {
        mc.repairs.zero_volume += n;
        mc.repairs.zero_volume_by_type[type] += n;
      }
    }
  } else if (options.strict)
    validate_tet_mesh(mc.mesh, mc.mesh_source, names);
  else
    mc.repairs = repair_tet_mesh(mc.mesh, mc.mesh_source, names);
  if (mc.split) mc.repairs.split_cells = mc.split->cells;
  if (!mc.cells) {  // own-interpolation cell meshes are walked by mesh/cell_traversal, not as tets
    mc.neighbors = tet_neighbors(mc.mesh, mc.mesh_source);
    refuse_overlapping_tets(mc.mesh, mc.neighbors, mc.mesh_source, names.tets);
  }
  if (const json* b = s.optional(root, "background")) mc.background = s.rgb(*b, "background");
  const json* rays = s.optional(root, "rays");
  if (const json* cam = s.optional(root, "camera")) mc.camera = s.camera(*cam, "camera");
  if (!rays && !mc.camera) s.fail(path, "a mesh case needs \"rays\" or a \"camera\"");
  if (rays) {
    s.non_empty_array(*rays, "rays", "");
    for (std::size_t i = 0; i < rays->size(); ++i) {
      const std::string rp = index_path("rays", i);
      const json& r = (*rays)[i];
      s.require_object(r, rp);
      s.check_fields(r, rp, {"origin", "direction", "background"});
      MeshViewRay v;
      v.ray.origin = s.vec3(s.required(r, rp, "origin"), member_path(rp, "origin"));
      v.ray.direction = s.direction(s.required(r, rp, "direction"), member_path(rp, "direction"));
      v.background = mc.background;
      if (const json* b = s.optional(r, "background")) v.background = s.rgb(*b, member_path(rp, "background"));
      mc.rays.push_back(v);
    }
    refuse_far_origins(mc, source);
  }
  if (const json* sh = s.optional(root, "shading")) mc.shading = shading(s, *sh, "shading");
  // Every command that integrates the own mode would otherwise drop the shading without a word.
  if (mc.cells && mc.shading.enabled)
    s.fail("shading", "not available in the own mode of cells other than tetrahedra (--cells split shades VTK's "
                      "tetrahedralisation of them)");
  return mc;
}

void refuse_far_origins(const MeshCase& mc, const std::string& source) {
  if (mc.mesh.points.empty()) return;
  Vec3 lo = mc.mesh.points.front(), hi = lo;
  for (const Vec3& p : mc.mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // A ray parameter t at distance D is represented to D * 2^-52 (one ulp, within a factor 2):
  // once that step exceeds the mesh's extent every crossing is lost and the ray returns its
  // background -- a silent miss (issue 30). The rule of the camera check (cli/render_mesh.cpp).
  const double extent = (hi - lo).norm();
  const Vec3 centre = (lo + hi) / 2;
  for (std::size_t i = 0; i < mc.rays.size(); ++i) {
    const double distance = (mc.rays[i].ray.origin - centre).norm();
    const double step = distance * std::numeric_limits<double>::epsilon();
    if (!(step < extent))
      throw InputError(source + ": " + index_path("rays", i) + ".origin: " + format_number(distance) +
                       " from the mesh (extent " + format_number(extent) + "): a double's step there (" +
                       format_number(step) + ") exceeds the mesh, the ray would miss it; move the origin closer");
  }
}

MeshCase read_mesh_case_file(const std::string& path, const MeshReadOptions& options) {
  return parse_mesh_case(json_source::parse(json_source::read_text_file(path), path), path, options);
}

void register_mesh_reader(const std::string& extension, MeshFileReader read) {
  extra_mesh_readers()[extension] = read;
}

}  // namespace rayint
