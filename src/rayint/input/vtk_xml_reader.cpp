// The .vtu and .vti readers (see vtk_xml_reader.hpp): the XML structure of each dataset; the
// DataArray bytes go through the one decoder of vtk_xml_data_array.hpp.
#include "rayint/input/vtk_xml_reader.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "rayint/core/error.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/input/vtk_xml_data_array.hpp"

namespace rayint {
namespace {

using vtk_xml::Document;

constexpr long long kMaxIndex = 2147483647;  // TetMesh indices are int32


// The DataArray child of `parent` named `name` (Cells: connectivity, offsets, types).
pugi::xml_node named_array(const Document& d, pugi::xml_node parent, const char* name, const std::string& field) {
  pugi::xml_node found;
  for (pugi::xml_node a = parent.child("DataArray"); a; a = a.next_sibling("DataArray"))
    if (std::strcmp(a.attribute("Name").as_string(), name) == 0) {
      if (found) d.fail(field + "/DataArray[" + name + "]", "more than one");
      found = a;
    }
  if (!found) d.fail(field + "/DataArray[" + name + "]", "missing");
  return found;
}

// The point scalar array (see the header for the choice) and its field name.
pugi::xml_node scalar_array(const Document& d, pugi::xml_node piece, const std::string& piece_field,
                            const std::string& scalar_name, std::string& field) {
  const std::string pd_field = piece_field + "/PointData";
  const pugi::xml_node pd = piece.child("PointData");
  std::string names;
  for (pugi::xml_node a = pd.child("DataArray"); a; a = a.next_sibling("DataArray"))
    names += std::string(names.empty() ? "" : ", ") + "\"" + a.attribute("Name").as_string() + "\"";
  const std::string wanted = !scalar_name.empty() ? scalar_name : pd.attribute("Scalars").as_string();
  pugi::xml_node chosen;
  for (pugi::xml_node a = pd.child("DataArray"); a && !wanted.empty(); a = a.next_sibling("DataArray"))
    if (a.attribute("Name").as_string() == wanted) {
      chosen = a;
      break;
    }
  if (!chosen && !scalar_name.empty())
    d.fail(pd_field, "no array named \"" + scalar_name + "\" (arrays: " + (names.empty() ? "none" : names) + ")");
  for (pugi::xml_node a = pd.child("DataArray"); a && !chosen; a = a.next_sibling("DataArray"))
    if (d.components(a, pd_field + "/DataArray") == 1) chosen = a;
  if (!chosen) d.fail(pd_field, "no one-component point array for the scalar (arrays: " + (names.empty() ? "none" : names) + ")");
  field = pd_field + "/DataArray[" + chosen.attribute("Name").as_string() + "]";
  const std::size_t comps = d.components(chosen, field);
  if (comps != 1) d.fail(field, "has " + std::to_string(comps) + " components, need 1");
  return chosen;
}

std::vector<double> finite_values(const Document& d, pugi::xml_node array, const std::string& field, std::size_t n) {
  std::vector<double> v = d.values(array, field, n);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) d.fail(field, "value " + std::to_string(i) + " is not finite");
  return v;
}

}  // namespace

TetMesh parse_vtu(std::string_view bytes, const std::string& source, const std::string& scalar_name) {
  const Document d(bytes, source, "UnstructuredGrid");
  const std::string piece_field = "UnstructuredGrid/Piece";
  const pugi::xml_node piece = d.only_child(d.dataset(), "Piece", "UnstructuredGrid");
  const auto n_points = static_cast<std::size_t>(d.count_attribute(piece, "NumberOfPoints", piece_field, kMaxIndex));
  const auto n_cells = static_cast<std::size_t>(d.count_attribute(piece, "NumberOfCells", piece_field, kMaxIndex / 4));

  TetMesh mesh;
  const std::string points_field = piece_field + "/Points/DataArray";
  const pugi::xml_node points = d.only_child(d.only_child(piece, "Points", piece_field), "DataArray", piece_field + "/Points");
  if (d.components(points, points_field) != 3)
    d.fail(points_field, "NumberOfComponents must be 3, got " + std::to_string(d.components(points, points_field)));
  const std::vector<double> xyz = finite_values(d, points, points_field, 3 * n_points);
  mesh.points.resize(n_points);
  for (std::size_t i = 0; i < n_points; ++i) mesh.points[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  const std::string cells_field = piece_field + "/Cells";
  const pugi::xml_node cells = d.only_child(piece, "Cells", piece_field);
  const std::string types_field = cells_field + "/DataArray[types]";
  const std::vector<double> types = d.values(named_array(d, cells, "types", cells_field), types_field, n_cells);
  for (std::size_t i = 0; i < n_cells; ++i)
    if (types[i] != 10) {
      const auto t = static_cast<long long>(types[i]);
      d.fail(types_field, "cell " + std::to_string(i) + " has cell type " + std::to_string(t) + " (" +
                              vtk_xml::cell_type_name(t) + "); only linear tetrahedra (type 10) are read");
    }
  const std::string offsets_field = cells_field + "/DataArray[offsets]";
  const std::vector<double> offsets = d.values(named_array(d, cells, "offsets", cells_field), offsets_field, n_cells);
  for (std::size_t i = 0; i < n_cells; ++i)
    if (offsets[i] != 4.0 * static_cast<double>(i + 1))
      d.fail(offsets_field, "offset " + std::to_string(i) + " is " + std::to_string(offsets[i]) + ", expected " +
                                std::to_string(4 * (i + 1)) + " (4 points per tetrahedron)");
  const std::string conn_field = cells_field + "/DataArray[connectivity]";
  const std::vector<double> conn = d.values(named_array(d, cells, "connectivity", cells_field), conn_field, 4 * n_cells);
  mesh.tets.resize(n_cells);
  for (std::size_t i = 0; i < 4 * n_cells; ++i) {
    if (!(conn[i] >= 0 && conn[i] < static_cast<double>(n_points)) || conn[i] != std::floor(conn[i]))
      d.fail(conn_field, "value " + std::to_string(i) + " (" + std::to_string(conn[i]) + ") is not a point index in [0, " +
                             std::to_string(n_points) + ")");
    mesh.tets[i / 4][i % 4] = static_cast<std::int32_t>(conn[i]);
  }

  std::string scalar_field;
  const pugi::xml_node scalars = scalar_array(d, piece, piece_field, scalar_name, scalar_field);
  mesh.scalars = finite_values(d, scalars, scalar_field, n_points);
  validate_tet_mesh_structure(mesh, source, MeshFieldNames{piece_field + "/Points", scalar_field, cells_field});
  return mesh;
}

TetMesh read_vtu(const std::string& path, const std::string& scalar_name) {
  return parse_vtu(json_source::read_text_file(path), path, scalar_name);
}

VoxelGrid parse_vti(std::string_view bytes, const std::string& source, const std::string& scalar_name) {
  const Document d(bytes, source, "ImageData");
  const pugi::xml_node image = d.dataset();
  const std::string field = "ImageData";
  const std::vector<double> extent = d.numbers_attribute(image, "WholeExtent", field, 6);
  const std::vector<double> origin = d.numbers_attribute(image, "Origin", field, 3, {0.0, 0.0, 0.0});
  const std::vector<double> spacing = d.numbers_attribute(image, "Spacing", field, 3, {1.0, 1.0, 1.0});
  const std::vector<double> direction =
      d.numbers_attribute(image, "Direction", field, 9, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  for (std::size_t i = 0; i < 9; ++i)
    if (direction[i] != (i % 4 == 0 ? 1.0 : 0.0))
      d.fail(field, "Direction is not the identity; rayint's voxel grids are axis-aligned (resample the image)");
  std::array<int, 3> dims{};
  long long total = 1;
  for (int a = 0; a < 3; ++a) {
    const double lo = extent[2 * a], hi = extent[2 * a + 1];
    if (lo != std::floor(lo) || hi != std::floor(hi) || std::fabs(lo) > 1e9 || std::fabs(hi) > 1e9 || hi - lo < 1)
      d.fail(field, "WholeExtent: each axis needs integer bounds lo < hi (at least 2 points)");
    dims[a] = static_cast<int>(hi - lo + 1);
    total *= dims[a];
    if (dims[a] > kMaxGridPoints || total > kMaxGridPoints)
      d.fail(field, "WholeExtent: more than " + std::to_string(kMaxGridPoints) + " points");
    if (!(spacing[a] > 0)) d.fail(field, "Spacing must be > 0 on every axis");
  }
  const Vec3 lower(origin[0] + extent[0] * spacing[0], origin[1] + extent[2] * spacing[1],
                   origin[2] + extent[4] * spacing[2]);
  const Vec3 step(spacing[0], spacing[1], spacing[2]);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(lower[a]) || !std::isfinite(lower[a] + (dims[a] - 1) * step[a]))
      d.fail(field, "the image's extent overflows");
  const std::string piece_field = "ImageData/Piece";
  const pugi::xml_node piece = d.only_child(image, "Piece", field);
  if (d.numbers_attribute(piece, "Extent", piece_field, 6) != extent)
    d.fail(piece_field, "Extent differs from the WholeExtent (only single-piece images are read)");
  std::string scalar_field;
  const pugi::xml_node scalars = scalar_array(d, piece, piece_field, scalar_name, scalar_field);
  std::vector<double> values = finite_values(d, scalars, scalar_field, static_cast<std::size_t>(total));
  return VoxelGrid(dims, lower, step, std::move(values));
}

VoxelGrid read_vti(const std::string& path, const std::string& scalar_name) {
  return parse_vti(json_source::read_text_file(path), path, scalar_name);
}

}  // namespace rayint
