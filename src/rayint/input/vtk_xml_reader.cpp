// The .vtu and .vti readers (see vtk_xml_reader.hpp): the XML structure of each dataset; the
// DataArray bytes go through the one decoder of vtk_xml_data_array.hpp.
#include "rayint/input/vtk_xml_reader.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <cstdint>
#include <cstring>
#include <functional>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/prefaulted.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/voxel_grid_reader.hpp"
#include "rayint/input/mesh_assembly.hpp"
#include "rayint/input/vtk_image_blanking.hpp"
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

// An array's values in a prefaulted buffer (core/prefaulted.hpp): the cell arrays, written in full.
// Below PrefaultedAllocator's 1 MiB (the types and offsets of a 105k-tet file: 0.84 MB each) the
// capacity is populated in one call (prefault_capacity) before resize writes it.
RawMesh::Array<double> cell_values(const Document& d, pugi::xml_node array, const std::string& field, std::size_t n) {
  RawMesh::Array<double> v;
  d.values_into(array, field, n, [&] {
    v.reserve(n);
    prefault_capacity(v);
    v.resize(n);
    return v.data();
  });
  return v;
}

}  // namespace

namespace {

// Every DataArray of a PointData / CellData element as RawArrays (values decoded for
// one-component arrays only: the others can never be the scalar, and are only listed). With
// `only`, only the arrays it accepts are decoded (the others are listed with no values).
void data_arrays(const Document& d, pugi::xml_node parent, bool cell, std::size_t tuples, const std::string& field,
                 std::vector<RawArray>& out, const std::function<bool(const RawArray&)>& only = {}) {
  const std::string active = parent.attribute("Scalars").as_string();
  for (pugi::xml_node a = parent.child("DataArray"); a; a = a.next_sibling("DataArray")) {
    RawArray r;
    r.name = a.attribute("Name").as_string();
    r.cell = cell;
    const std::string f = field + "/DataArray[" + r.name + "]";
    r.components = d.components(a, f);
    r.active = !active.empty() && r.name == active;
    if (r.components == 1 && (!only || only(r))) r.values = d.values(a, f, tuples);
    out.push_back(std::move(r));
  }
}

// One <Piece> of an UnstructuredGrid appended to `raw` (point indices offset by the points
// already there; arrays matched by name and association across pieces).
// Only the arrays the assembly reads are decoded (issue 33): the scalar (find_scalar_array on
// the first piece's arrays, whose choice the assembly makes) and the ghost flags.
void append_vtu_piece(const Document& d, pugi::xml_node piece, const std::string& piece_field, RawMesh& raw,
                      const AssemblyOptions& options) {
  const auto n_points = static_cast<std::size_t>(d.count_attribute(piece, "NumberOfPoints", piece_field, kMaxIndex));
  const auto n_cells = static_cast<std::size_t>(d.count_attribute(piece, "NumberOfCells", piece_field, kMaxIndex / 4));
  const std::string points_field = piece_field + "/Points/DataArray";
  const pugi::xml_node points = d.only_child(d.only_child(piece, "Points", piece_field), "DataArray", piece_field + "/Points");
  if (d.components(points, points_field) != 3)
    d.fail(points_field, "NumberOfComponents must be 3, got " + std::to_string(d.components(points, points_field)));
  // Decoded straight into the points (Vec3: three packed doubles), then checked as finite_values does.
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 holds three doubles, unpadded");
  const std::size_t base = raw.points.size();
  d.values_into(points, points_field, 3 * n_points, [&]() -> double* {
    if (base == 0) {  // the first piece: its points written in full, populated in one call
      raw.points.reserve(n_points);
      prefault_capacity(raw.points);
    }
    raw.points.resize(base + n_points);
    return n_points == 0 ? nullptr : raw.points[base].data();
  });
  for (std::size_t i = 0; i < 3 * n_points; ++i)
    if (!std::isfinite(raw.points[base + i / 3][static_cast<Eigen::Index>(i % 3)]))
      d.fail(points_field, "value " + std::to_string(i) + " is not finite");

  const std::string cells_field = piece_field + "/Cells";
  const pugi::xml_node cells = d.only_child(piece, "Cells", piece_field);
  const std::string types_field = cells_field + "/DataArray[types]";
  const auto types = cell_values(d, named_array(d, cells, "types", cells_field), types_field, n_cells);
  const std::string offsets_field = cells_field + "/DataArray[offsets]";
  const auto offsets = cell_values(d, named_array(d, cells, "offsets", cells_field), offsets_field, n_cells);
  // The connectivity's length is the last offset (VTK XML stores each cell's end offset).
  double prev = 0.0;
  for (std::size_t i = 0; i < n_cells; ++i) {
    if (!(offsets[i] >= prev) || offsets[i] != std::floor(offsets[i]) || offsets[i] > 64.0 * static_cast<double>(kMaxIndex))
      d.fail(offsets_field, "offset " + std::to_string(i) + " (" + std::to_string(offsets[i]) +
                                ") does not follow the previous one (" + std::to_string(prev) + ")");
    prev = offsets[i];
  }
  const auto n_conn = static_cast<std::size_t>(prev);
  const std::string conn_field = cells_field + "/DataArray[connectivity]";
  const pugi::xml_node conn_array = named_array(d, cells, "connectivity", cells_field);
  if (n_conn > 8 * d.source_size() + 64)
    d.fail(offsets_field, "the last offset (" + std::to_string(n_conn) + ") is more than the file could hold");
  const auto conn = cell_values(d, conn_array, conn_field, n_conn);
  std::size_t start = raw.connectivity.size();
  // Reserved: growing by push_back touched about twice the final pages and copied them (issue 33).
  raw.connectivity.reserve(start + n_conn);
  raw.types.reserve(raw.types.size() + n_cells);
  raw.offsets.reserve(raw.offsets.size() + n_cells);
  prefault_capacity(raw.types);  // below PrefaultedAllocator's 1 MiB at 105k tets
  prefault_capacity(raw.offsets);
  for (std::size_t i = 0; i < n_conn; ++i) {
    if (!(conn[i] >= 0 && conn[i] < static_cast<double>(n_points)) || conn[i] != std::floor(conn[i]))
      d.fail(conn_field, "value " + std::to_string(i) + " (" + std::to_string(conn[i]) + ") is not a point index in [0, " +
                             std::to_string(n_points) + ")");
    raw.connectivity.push_back(static_cast<long long>(conn[i]) + static_cast<long long>(base));
  }
  for (std::size_t i = 0; i < n_cells; ++i) {
    if (!(types[i] >= 0 && types[i] <= 1e6 && types[i] == std::floor(types[i])))
      d.fail(types_field, "value " + std::to_string(i) + " is not a cell type");
    raw.types.push_back(static_cast<long long>(types[i]));
    raw.offsets.push_back(start + static_cast<std::size_t>(offsets[i]));
  }

  const bool first = base == 0 && start == 0;
  std::vector<RawArray> arrays;
  if (first) {  // the listing first, to choose from
    if (const pugi::xml_node pd = piece.child("PointData"))
      data_arrays(d, pd, false, n_points, piece_field + "/PointData", arrays, [](const RawArray&) { return false; });
    if (const pugi::xml_node cd = piece.child("CellData"))
      data_arrays(d, cd, true, n_cells, piece_field + "/CellData", arrays, [](const RawArray&) { return false; });
  }
  const RawArray* scalar = find_scalar_array(first ? arrays : raw.arrays, options);
  const std::string scalar_name = scalar != nullptr ? scalar->name : "";
  const bool scalar_cell = scalar != nullptr && scalar->cell;
  const auto used = [&](const RawArray& a) {
    return (scalar != nullptr && a.name == scalar_name && a.cell == scalar_cell) || (a.cell && a.name == "vtkGhostType");
  };
  arrays.clear();
  if (const pugi::xml_node pd = piece.child("PointData")) data_arrays(d, pd, false, n_points, piece_field + "/PointData", arrays, used);
  if (const pugi::xml_node cd = piece.child("CellData")) data_arrays(d, cd, true, n_cells, piece_field + "/CellData", arrays, used);
  if (first) {
    raw.arrays = std::move(arrays);
    return;
  }
  // Later pieces: the same arrays, values appended.
  for (RawArray& r : raw.arrays) {
    RawArray* match = nullptr;
    for (RawArray& a : arrays)
      if (a.name == r.name && a.cell == r.cell) match = &a;
    if (match == nullptr || match->components != r.components)
      d.fail(piece_field, std::string(r.cell ? "CellData" : "PointData") + " array \"" + r.name +
                              "\" is missing or has another component count in this piece");
    r.values.insert(r.values.end(), match->values.begin(), match->values.end());
  }
}

RawMeshFields vtu_fields(const std::string& piece_field) {
  RawMeshFields f;
  f.points = piece_field + "/Points";
  f.point_data = piece_field + "/PointData";
  f.cell_data = piece_field + "/CellData";
  f.cells = piece_field + "/Cells";
  f.types = piece_field + "/Cells/DataArray[types]";
  return f;
}

}  // namespace

namespace {

// A .vtu's pieces as one RawMesh, handed to `assemble` (assemble_tet_mesh or assemble_cell_mesh).
template <class Assemble>
auto assemble_vtu(std::string_view bytes, const std::string& source, const ScalarChoice& scalar, Assemble assemble) {
  const Document d(bytes, source, "UnstructuredGrid");
  const std::string piece_field = "UnstructuredGrid/Piece";
  RawMesh raw;
  std::size_t pieces = 0;
  AssemblyOptions o;
  o.scalar = scalar;
  for (pugi::xml_node piece = d.dataset().child("Piece"); piece; piece = piece.next_sibling("Piece")) {
    append_vtu_piece(d, piece, pieces == 0 ? piece_field : piece_field + "[" + std::to_string(pieces) + "]", raw, o);
    ++pieces;
  }
  if (pieces == 0) d.fail(piece_field, "missing");
  o.merge_points = pieces > 1;
  return assemble(std::move(raw), source, o, vtu_fields(piece_field));
}

}  // namespace

TetMesh parse_vtu(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return assemble_vtu(bytes, source, scalar, &assemble_tet_mesh);
}

CellMesh parse_vtu_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return assemble_vtu(bytes, source, scalar, &assemble_cell_mesh);
}

CellMesh read_vtu_cells(const std::string& path, const ScalarChoice& scalar) {
  return parse_vtu_cells(json_source::read_big_file(path), path, scalar);
}

TetMesh read_vtu(const std::string& path, const ScalarChoice& scalar) {
  return parse_vtu(json_source::read_big_file(path), path, scalar);
}

namespace {

// The Source files a parallel file (.pvtu, .pvti) names, resolved against its folder.
std::vector<std::string> piece_sources(const Document& d, pugi::xml_node dataset, const std::string& field,
                                       const std::string& path) {
  std::vector<std::string> out;
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  for (pugi::xml_node p = dataset.child("Piece"); p; p = p.next_sibling("Piece")) {
    const std::string src = p.attribute("Source").as_string();
    if (src.empty()) d.fail(field + "/Piece", "missing attribute Source");
    const std::filesystem::path sp(src);
    out.push_back((sp.is_absolute() ? sp : dir / sp).string());
  }
  if (out.empty()) d.fail(field + "/Piece", "missing (a parallel file names its pieces)");
  return out;
}

}  // namespace

namespace {

template <class Assemble>
auto assemble_pvtu(const std::string& path, const ScalarChoice& scalar, Assemble assemble) {
  const std::string text = json_source::read_text_file(path);
  const Document d(text, path, "PUnstructuredGrid");
  RawMesh raw;
  std::size_t pieces = 0;
  std::string last_field = "UnstructuredGrid/Piece";
  AssemblyOptions o;
  o.scalar = scalar;
  for (const std::string& file : piece_sources(d, d.dataset(), "PUnstructuredGrid", path)) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      d.fail("PUnstructuredGrid/Piece", "the piece " + file + " does not exist");
    const std::string piece_text = json_source::read_text_file(file);
    const Document pd(piece_text, file, "UnstructuredGrid");
    for (pugi::xml_node piece = pd.dataset().child("Piece"); piece; piece = piece.next_sibling("Piece")) {
      append_vtu_piece(pd, piece, "UnstructuredGrid/Piece", raw, o);
      ++pieces;
    }
  }
  o.merge_points = true;
  RawMeshFields f = vtu_fields(last_field);
  return assemble(std::move(raw), path + " (" + std::to_string(pieces) + " pieces)", o, f);
}

}  // namespace

std::vector<std::string> pvtu_piece_files(const std::string& path) {
  const std::string text = json_source::read_text_file(path);
  const Document d(text, path, "PUnstructuredGrid");
  return piece_sources(d, d.dataset(), "PUnstructuredGrid", path);
}

TetMesh read_pvtu(const std::string& path, const ScalarChoice& scalar) {
  return assemble_pvtu(path, scalar, &assemble_tet_mesh);
}

CellMesh read_pvtu_cells(const std::string& path, const ScalarChoice& scalar) {
  return assemble_pvtu(path, scalar, &assemble_cell_mesh);
}

namespace {

// The geometry of an image: WholeExtent, Origin, Spacing, Direction (row-major, as VTK writes
// it: world = Origin + Direction (index * spacing); orthonormal, else refused).
struct ImageFrame {
  std::vector<double> extent, origin, spacing, direction;
  std::array<int, 3> dims{};
  long long total = 1;
};

Eigen::Matrix3d direction_matrix(const std::vector<double>& rows) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = rows[static_cast<std::size_t>(3 * r + c)];
  return m;
}

ImageFrame image_frame(const Document& d, pugi::xml_node image, const std::string& field) {
  ImageFrame f;
  f.extent = d.numbers_attribute(image, "WholeExtent", field, 6);
  f.origin = d.numbers_attribute(image, "Origin", field, 3, {0.0, 0.0, 0.0});
  f.spacing = d.numbers_attribute(image, "Spacing", field, 3, {1.0, 1.0, 1.0});
  f.direction = d.numbers_attribute(image, "Direction", field, 9, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  const std::string why = check_direction(direction_matrix(f.direction));
  if (!why.empty()) d.fail(field, why);
  for (std::size_t a = 0; a < 3; ++a) {
    const double lo = f.extent[2 * a], hi = f.extent[2 * a + 1];
    if (lo != std::floor(lo) || hi != std::floor(hi) || std::fabs(lo) > 1e9 || std::fabs(hi) > 1e9 || hi - lo < 1)
      d.fail(field, "WholeExtent: each axis needs integer bounds lo < hi (at least 2 points)");
    f.dims[a] = static_cast<int>(hi - lo + 1);
    f.total *= f.dims[a];
    if (f.dims[a] > kMaxGridPoints || f.total > kMaxGridPoints)
      d.fail(field, "WholeExtent: more than " + std::to_string(kMaxGridPoints) + " points");
    if (!(f.spacing[a] > 0)) d.fail(field, "Spacing must be > 0 on every axis");
  }
  return f;
}

VoxelGrid make_grid(const Document& d, const ImageFrame& f, std::vector<double> values, const std::string& field) {
  const Vec3 lower(f.origin[0] + f.extent[0] * f.spacing[0], f.origin[1] + f.extent[2] * f.spacing[1],
                   f.origin[2] + f.extent[4] * f.spacing[2]);
  const Vec3 step(f.spacing[0], f.spacing[1], f.spacing[2]);
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(lower[a]) || !std::isfinite(lower[a] + (f.dims[static_cast<std::size_t>(a)] - 1) * step[a]))
      d.fail(field, "the image's extent overflows");
  VoxelGrid grid(f.dims, lower, step, std::move(values));
  GridPlacement placement;
  placement.direction = direction_matrix(f.direction);
  placement.pivot = Vec3(f.origin[0], f.origin[1], f.origin[2]);
  if (!placement.identity()) grid.set_placement(placement);
  return grid;
}

// The point scalar of an image piece (PointData; an image with cell data only is refused naming
// its arrays: a voxel grid holds values at points).
std::vector<double> image_piece_values(const Document& d, pugi::xml_node piece, const std::string& piece_field,
                                       const std::string& scalar_name, std::size_t n) {
  const pugi::xml_node pd = piece.child("PointData");
  bool any_point = false;
  for (pugi::xml_node a = pd.child("DataArray"); a; a = a.next_sibling("DataArray")) any_point = true;
  if (!any_point) {
    std::string cells;
    for (pugi::xml_node a = piece.child("CellData").child("DataArray"); a; a = a.next_sibling("DataArray"))
      cells += std::string(cells.empty() ? "" : ", ") + "\"" + a.attribute("Name").as_string() + "\"";
    if (!cells.empty())
      d.fail(piece_field + "/CellData", "an image with cell data only (" + cells +
                                            ") is not a voxel grid (values at points): use it as a mesh case's "
                                            "\"mesh_file\" with --cells split (constant per voxel, exact)");
  }
  std::string scalar_field;
  const pugi::xml_node scalars = scalar_array(d, piece, piece_field, scalar_name, scalar_field);
  return finite_values(d, scalars, scalar_field, n);
}

}  // namespace

VoxelGrid parse_vti(std::string_view bytes, const std::string& source, const std::string& scalar_name) {
  const Document d(bytes, source, "ImageData");
  const std::string field = "ImageData";
  const ImageFrame f = image_frame(d, d.dataset(), field);
  const std::string piece_field = "ImageData/Piece";
  const pugi::xml_node piece = d.only_child(d.dataset(), "Piece", field);
  if (d.numbers_attribute(piece, "Extent", piece_field, 6) != f.extent)
    d.fail(piece_field, "Extent differs from the WholeExtent (only single-piece images are read; a .pvti joins pieces)");
  VoxelGrid grid = make_grid(d, f, image_piece_values(d, piece, piece_field, scalar_name, static_cast<std::size_t>(f.total)), field);
  const ImageGhosts ghosts = read_image_ghosts(d, piece, piece_field, f.dims);  // blanking: vtk_image_blanking.hpp
  grid.set_hidden_cubes(hidden_cubes(f.dims, ghosts.hidden_points, ghosts.hidden_cells));
  return grid;
}

VoxelGrid read_pvti(const std::string& path, const std::string& scalar_name) {
  const std::string text = json_source::read_text_file(path);
  const Document d(text, path, "PImageData");
  const std::string field = "PImageData";
  const ImageFrame f = image_frame(d, d.dataset(), field);
  std::vector<double> values(static_cast<std::size_t>(f.total), 0.0);
  std::vector<char> set(values.size(), 0);
  // Blanking (vtk_image_blanking.hpp), each piece's hidden points and cells placed in the whole.
  std::vector<unsigned char> hidden_points(values.size(), 0);
  std::vector<unsigned char> hidden_cells(static_cast<std::size_t>(f.dims[0] - 1) * static_cast<std::size_t>(f.dims[1] - 1) *
                                          static_cast<std::size_t>(f.dims[2] - 1), 0);
  for (const std::string& file : piece_sources(d, d.dataset(), field, path)) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) d.fail(field + "/Piece", "the piece " + file + " does not exist");
    const std::string piece_text = json_source::read_text_file(file);
    const Document pd(piece_text, file, "ImageData");
    const std::string piece_field = "ImageData/Piece";
    const pugi::xml_node piece = pd.only_child(pd.dataset(), "Piece", "ImageData");
    const std::vector<double> e = pd.numbers_attribute(piece, "Extent", piece_field, 6);
    std::array<long long, 3> lo{}, n{};
    long long count = 1;
    for (std::size_t a = 0; a < 3; ++a) {
      if (e[2 * a] != std::floor(e[2 * a]) || e[2 * a + 1] != std::floor(e[2 * a + 1]) || e[2 * a] < f.extent[2 * a] ||
          e[2 * a + 1] > f.extent[2 * a + 1] || e[2 * a + 1] < e[2 * a])
        pd.fail(piece_field, "Extent lies outside the WholeExtent of " + path);
      lo[a] = static_cast<long long>(e[2 * a] - f.extent[2 * a]);
      n[a] = static_cast<long long>(e[2 * a + 1] - e[2 * a]) + 1;
      count *= n[a];
    }
    const std::vector<double> v = image_piece_values(pd, piece, piece_field, scalar_name, static_cast<std::size_t>(count));
    std::size_t q = 0;
    for (long long k = 0; k < n[2]; ++k)
      for (long long j = 0; j < n[1]; ++j)
        for (long long i = 0; i < n[0]; ++i, ++q) {
          const auto at = static_cast<std::size_t>((lo[0] + i) + f.dims[0] * ((lo[1] + j) + f.dims[1] * (lo[2] + k)));
          if (set[at] && !(values[at] == v[q]))
            pd.fail(piece_field, "a point shared with another piece has another value");
          values[at] = v[q];
          set[at] = 1;
        }
    const std::array<int, 3> piece_dims{static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2])};
    const ImageGhosts ghosts = read_image_ghosts(pd, piece, piece_field, piece_dims);
    for (long long k = 0; k < n[2]; ++k)
      for (long long j = 0; j < n[1]; ++j)
        for (long long i = 0; i < n[0]; ++i) {
          const auto local = static_cast<std::size_t>(i + n[0] * (j + n[1] * k));
          if (!ghosts.hidden_points.empty() && ghosts.hidden_points[local] != 0)
            hidden_points[static_cast<std::size_t>((lo[0] + i) + f.dims[0] * ((lo[1] + j) + f.dims[1] * (lo[2] + k)))] = 1;
          if (!ghosts.hidden_cells.empty() && i + 1 < n[0] && j + 1 < n[1] && k + 1 < n[2] &&
              ghosts.hidden_cells[static_cast<std::size_t>(i + (n[0] - 1) * (j + (n[1] - 1) * k))] != 0)
            hidden_cells[static_cast<std::size_t>((lo[0] + i) + (f.dims[0] - 1) * ((lo[1] + j) + (f.dims[1] - 1) * (lo[2] + k)))] = 1;
        }
  }
  for (std::size_t i = 0; i < set.size(); ++i)
    if (!set[i]) d.fail(field, "the pieces do not cover the WholeExtent (point " + std::to_string(i) + " missing)");
  VoxelGrid grid = make_grid(d, f, std::move(values), field);
  grid.set_hidden_cubes(hidden_cubes(f.dims, hidden_points, hidden_cells));
  return grid;
}

VoxelGrid read_vti(const std::string& path, const std::string& scalar_name) {
  return parse_vti(json_source::read_text_file(path), path, scalar_name);
}

}  // namespace rayint

namespace rayint {
namespace {

// The point dimensions of a structured dataset's single Piece, whose Extent must be its
// WholeExtent (what vtkXMLStructuredGridWriter / vtkXMLRectilinearGridWriter write for one
// dataset). A grid flat on some axis (one point) has no volume cells and is refused.
std::array<int, 3> structured_dims(const Document& d, const std::string& type, pugi::xml_node& piece) {
  const std::string piece_field = type + "/Piece";
  const std::vector<double> whole = d.numbers_attribute(d.dataset(), "WholeExtent", type, 6);
  piece = d.only_child(d.dataset(), "Piece", type);
  const std::vector<double> extent = d.numbers_attribute(piece, "Extent", piece_field, 6, whole);
  if (extent != whole)
    d.fail(piece_field, "Extent differs from the WholeExtent (a piece of a larger grid: read the .pvts / .pvtr that names it)");
  std::array<int, 3> dims{};
  double total = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    const double lo = extent[2 * a], hi = extent[2 * a + 1];
    if (lo != std::floor(lo) || hi != std::floor(hi) || !(hi >= lo) || hi - lo > 1e7)
      d.fail(piece_field, "Extent is not an integer range on axis " + std::to_string(a));
    if (hi == lo)
      d.fail(piece_field, std::string("Extent is flat on axis ") + "xyz"[a] +
                              " (a 2-D grid has no volume cells; rayint integrates volumes)");
    dims[a] = static_cast<int>(hi - lo) + 1;
    total *= dims[a];
  }
  if (total > static_cast<double>(kMaxIndex) / 8) d.fail(piece_field, "more points than rayint's meshes hold (2^31 / 8)");
  return dims;
}

// The cells of the (nx, ny, nz) grid in VTK's order: vtkStructuredGrid::GetCell gives hexahedra
// (i,j,k) (i+1,j,k) (i+1,j+1,k) (i,j+1,k) then the same at k+1; vtkRectilinearGrid::GetCell
// voxels (i,j,k) (i+1,j,k) (i,j+1,k) (i+1,j+1,k) then k+1. Cell (i, j, k) is number
// i + (nx-1) (j + (ny-1) k), the order of the file's CellData.
void structured_cells(const std::array<int, 3>& n, bool voxels, RawMesh& raw) {
  const long long nx = n[0], ny = n[1], nz = n[2], sx = 1, sy = nx, sz = nx * ny;
  for (long long k = 0; k + 1 < nz; ++k)
    for (long long j = 0; j + 1 < ny; ++j)
      for (long long i = 0; i + 1 < nx; ++i) {
        const long long p = i * sx + j * sy + k * sz;
        const long long q[4] = {p, p + sx, voxels ? p + sy : p + sx + sy, voxels ? p + sx + sy : p + sy};
        for (long long z : {0LL, sz})
          for (long long v : q) raw.connectivity.push_back(v + z);
        raw.types.push_back(voxels ? kVtkVoxel : kVtkHexahedron);
        raw.offsets.push_back(raw.connectivity.size());
      }
}

RawMeshFields structured_fields(const std::string& type) {
  RawMeshFields f;
  f.points = type + (type == "RectilinearGrid" ? "/Piece/Coordinates" : "/Piece/Points");
  f.point_data = type + "/Piece/PointData";
  f.cell_data = type + "/Piece/CellData";
  f.cells = type + "/Piece (cells)";
  f.types = type + "/Piece (cell types)";
  return f;
}

void structured_arrays(const Document& d, pugi::xml_node piece, const std::string& type, std::size_t points,
                       std::size_t cells, RawMesh& raw) {
  if (const pugi::xml_node pd = piece.child("PointData")) data_arrays(d, pd, false, points, type + "/Piece/PointData", raw.arrays);
  if (const pugi::xml_node cd = piece.child("CellData")) data_arrays(d, cd, true, cells, type + "/Piece/CellData", raw.arrays);
}

std::size_t cell_total(const std::array<int, 3>& n) {
  return static_cast<std::size_t>(n[0] - 1) * static_cast<std::size_t>(n[1] - 1) * static_cast<std::size_t>(n[2] - 1);
}

// The cells of the n[0] x n[1] x n[2] points (voxels, or hexahedra when not axis-aligned) and
// the assembly, once points and arrays are in `raw` (the serial readers and the parallel ones).
CellMesh assemble_structured(const std::array<int, 3>& n, bool voxels, RawMesh raw, const std::string& source,
                             const ScalarChoice& scalar, const RawMeshFields& fields) {
  structured_cells(n, voxels, raw);
  AssemblyOptions o;
  o.scalar = scalar;
  CellMesh mesh = assemble_cell_mesh(std::move(raw), source, o, fields);
  mesh.structured = n;
  return mesh;
}

// The part every serial structured reader shares once its points are placed: the piece's point
// and cell arrays, then assemble_structured.
CellMesh structured_mesh(const Document& d, pugi::xml_node piece, const std::string& type,
                         const std::array<int, 3>& n, bool voxels, RawMesh raw, const std::string& source,
                         const ScalarChoice& scalar, const RawMeshFields& fields) {
  const std::size_t points = raw.points.size();
  structured_arrays(d, piece, type, points, cell_total(n), raw);
  return assemble_structured(n, voxels, std::move(raw), source, scalar, fields);
}

// A StructuredGrid piece's points (Points: one three-component DataArray, finite).
std::vector<Vec3> structured_points(const Document& d, pugi::xml_node piece, const std::string& type,
                                    const std::array<int, 3>& n) {
  const std::size_t points = static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(n[2]);
  const std::string points_field = type + "/Piece/Points/DataArray";
  const pugi::xml_node pts = d.only_child(d.only_child(piece, "Points", type + "/Piece"), "DataArray", type + "/Piece/Points");
  if (d.components(pts, points_field) != 3)
    d.fail(points_field, "NumberOfComponents must be 3, got " + std::to_string(d.components(pts, points_field)));
  const std::vector<double> xyz = finite_values(d, pts, points_field, 3 * points);
  std::vector<Vec3> out;
  out.reserve(points);
  for (std::size_t i = 0; i < points; ++i) out.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return out;
}

// A RectilinearGrid piece's Coordinates: three DataArrays, x, y, z in that order, whatever their
// names (VTK's writer calls them after the input's arrays; ParaView writes "Array 0x..." or
// "x_coordinates"), one component, finite, strictly increasing.
std::array<std::vector<double>, 3> rectilinear_axes(const Document& d, pugi::xml_node piece, const std::string& type,
                                                    const std::array<int, 3>& n) {
  const std::string coords_field = type + "/Piece/Coordinates";
  const pugi::xml_node coords = d.only_child(piece, "Coordinates", type + "/Piece");
  std::array<std::vector<double>, 3> axis;
  std::size_t a = 0;
  for (pugi::xml_node arr = coords.child("DataArray"); arr; arr = arr.next_sibling("DataArray"), ++a) {
    const std::string f = coords_field + "/DataArray[" + std::to_string(a) + "]";
    if (a >= 3) d.fail(f, "more than three coordinate arrays (x, y, z)");
    if (d.components(arr, f) != 1) d.fail(f, "a coordinate array has one component");
    axis[a] = finite_values(d, arr, f, static_cast<std::size_t>(n[a]));
    for (std::size_t i = 1; i < axis[a].size(); ++i)
      if (!(axis[a][i] > axis[a][i - 1]))
        d.fail(f, "coordinates must increase (value " + std::to_string(i) + " is not above the one before)");
  }
  if (a != 3) d.fail(coords_field, "needs three DataArrays (x, y, z), got " + std::to_string(a));
  return axis;
}

// The points of a rectilinear grid, x fastest (vtkRectilinearGrid's order).
std::vector<Vec3> rectilinear_points(const std::array<std::vector<double>, 3>& axis) {
  std::vector<Vec3> out;
  out.reserve(axis[0].size() * axis[1].size() * axis[2].size());
  for (double z : axis[2])
    for (double y : axis[1])
      for (double x : axis[0]) out.emplace_back(x, y, z);
  return out;
}

// A serial StructuredGrid or RectilinearGrid (voxels: its cells are axis-aligned): the piece and
// its dimensions (structured_dims), its points as points_of(d, piece, type, n) gives them, then
// structured_mesh.
template <class Points>
CellMesh parse_grid(std::string_view bytes, const std::string& source, const ScalarChoice& scalar, const std::string& type, bool voxels, Points points_of) {
  const Document d(bytes, source, type);
  pugi::xml_node piece;
  const std::array<int, 3> n = structured_dims(d, type, piece);
  RawMesh raw;
  raw.points = points_of(d, piece, type, n);
  return structured_mesh(d, piece, type, n, voxels, std::move(raw), source, scalar,
                         structured_fields(type));
}

}  // namespace

CellMesh parse_vts(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return parse_grid(bytes, source, scalar, "StructuredGrid", false, structured_points);
}

CellMesh parse_vtr(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  return parse_grid(bytes, source, scalar, "RectilinearGrid", true,
                    [](const Document& d, pugi::xml_node piece, const std::string& type, const std::array<int, 3>& n) {
                      return rectilinear_points(rectilinear_axes(d, piece, type, n));
                    });
}

CellMesh parse_vti_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  const std::string type = "ImageData";
  const Document d(bytes, source, type);
  const ImageFrame f = image_frame(d, d.dataset(), type);
  const std::string piece_field = type + "/Piece";
  const pugi::xml_node piece = d.only_child(d.dataset(), "Piece", type);
  if (d.numbers_attribute(piece, "Extent", piece_field, 6) != f.extent)
    d.fail(piece_field, "Extent differs from the WholeExtent (only single-piece images are read)");
  const std::array<int, 3> n = f.dims;
  if (static_cast<double>(f.total) > static_cast<double>(kMaxIndex) / 8)
    d.fail(piece_field, "more points than rayint's meshes hold (2^31 / 8)");
  // VTK's point (i, j, k) of the extent: Origin + Direction (index * spacing), index counted from
  // 0 at Extent 0 (vtkImageData::TransformIndexToPhysicalPoint).
  const Eigen::Matrix3d dir = direction_matrix(f.direction);
  const bool axis_aligned = dir == Eigen::Matrix3d::Identity();
  const Vec3 origin(f.origin[0], f.origin[1], f.origin[2]);
  RawMesh raw;
  raw.points.reserve(static_cast<std::size_t>(f.total));
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Vec3 step((f.extent[0] + i) * f.spacing[0], (f.extent[2] + j) * f.spacing[1], (f.extent[4] + k) * f.spacing[2]);
        const Vec3 p = axis_aligned ? Vec3(origin + step) : Vec3(origin + dir * step);
        if (!p.allFinite()) d.fail(type, "the image's extent overflows");
        raw.points.push_back(p);
      }
  // Voxels (vtkImageData::GetCell's order) when axis-aligned; a rotated voxel as the hexahedron
  // of the same corners.
  RawMeshFields fields = structured_fields(type);
  fields.points = type + " (Origin, Spacing, Direction)";
  return structured_mesh(d, piece, type, n, axis_aligned, std::move(raw), source, scalar, fields);
}

CellMesh read_vti_cells(const std::string& path, const ScalarChoice& scalar) {
  return parse_vti_cells(json_source::read_text_file(path), path, scalar);
}

CellMesh read_vts(const std::string& path, const ScalarChoice& scalar) {
  return parse_vts(json_source::read_text_file(path), path, scalar);
}

CellMesh read_vtr(const std::string& path, const ScalarChoice& scalar) {
  return parse_vtr(json_source::read_text_file(path), path, scalar);
}

// ---- Parallel structured grids (.pvts, .pvtr) ----------------------------------------------------

namespace {

constexpr unsigned kDuplicateBit = 1;  // vtkDataSetAttributes::DUPLICATEPOINT / DUPLICATECELL

bool is_ghost_array(const RawArray& a) { return a.name == "vtkGhostType"; }

bool same_value(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// One piece of a parallel structured file, read whole before anything is placed (so the whole
// grid is only allocated once the pieces have shown that they hold its points).
struct StructuredPiece {
  std::string file;
  std::array<long long, 3> lo{};  // its Extent's lower bounds, relative to the WholeExtent's
  std::array<int, 3> n{};         // its point dimensions
  std::vector<Vec3> points;                 // StructuredGrid
  std::array<std::vector<double>, 3> axis;  // RectilinearGrid
  std::vector<RawArray> arrays;
};

CellMesh parse_parallel_structured(std::string_view bytes, const std::string& source, const PieceFileLoader& load,
                                   bool rectilinear, const ScalarChoice& scalar) {
  const std::string type = rectilinear ? "RectilinearGrid" : "StructuredGrid";
  const std::string ptype = "P" + type;
  const Document d(bytes, source, ptype);
  const std::vector<double> whole = d.numbers_attribute(d.dataset(), "WholeExtent", ptype, 6);
  std::array<int, 3> N{};
  std::array<long long, 3> lo{};
  double total = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    const double w0 = whole[2 * a], w1 = whole[2 * a + 1];
    if (w0 != std::floor(w0) || w1 != std::floor(w1) || !(w1 >= w0) || w1 - w0 > 1e7 || std::fabs(w0) > 1e9)
      d.fail(ptype, "WholeExtent is not an integer range on axis " + std::to_string(a));
    if (w1 == w0)
      d.fail(ptype, std::string("WholeExtent is flat on axis ") + "xyz"[a] + " (a 2-D grid has no volume cells; rayint integrates volumes)");
    N[a] = static_cast<int>(w1 - w0) + 1;
    lo[a] = static_cast<long long>(w0);
    total *= N[a];
  }
  if (total > static_cast<double>(kMaxIndex) / 8) d.fail(ptype, "more points than rayint's meshes hold (2^31 / 8)");

  // The pieces, each a serial file of the same type whose Extent lies in the WholeExtent.
  const std::filesystem::path dir = std::filesystem::path(source).parent_path();
  std::vector<StructuredPiece> pieces;
  double covered = 0;
  for (pugi::xml_node p = d.dataset().child("Piece"); p; p = p.next_sibling("Piece")) {
    const std::string field = ptype + "/Piece[" + std::to_string(pieces.size()) + "]";
    const std::vector<double> e = d.numbers_attribute(p, "Extent", field, 6);
    bool empty = false;
    for (std::size_t a = 0; a < 3; ++a) empty = empty || e[2 * a + 1] < e[2 * a];
    if (empty) continue;  // VTK writes an empty extent for a piece with no cells
    const std::string src = p.attribute("Source").as_string();
    if (src.empty()) d.fail(field, "missing attribute Source");
    for (char c : src)
      if (static_cast<unsigned char>(c) < 0x20) d.fail(field, "Source contains a control character");
    const std::filesystem::path sp(src);
    StructuredPiece piece;
    piece.file = (sp.is_absolute() ? sp : dir / sp).string();
    const std::string text = load(piece.file);
    const Document pd(text, piece.file, type);
    pugi::xml_node node;
    piece.n = structured_dims(pd, type, node);
    const std::vector<double> pe = pd.numbers_attribute(node, "Extent", type + "/Piece", 6);
    if (pe != e) pd.fail(type + "/Piece", "Extent differs from the one " + source + " gives this piece");
    for (std::size_t a = 0; a < 3; ++a) {
      if (pe[2 * a] < whole[2 * a] || pe[2 * a + 1] > whole[2 * a + 1])
        pd.fail(type + "/Piece", "Extent lies outside the WholeExtent of " + source);
      piece.lo[a] = static_cast<long long>(pe[2 * a]) - lo[a];
    }
    if (rectilinear) piece.axis = rectilinear_axes(pd, node, type, piece.n);
    else piece.points = structured_points(pd, node, type, piece.n);
    const std::size_t points = static_cast<std::size_t>(piece.n[0]) * static_cast<std::size_t>(piece.n[1]) * static_cast<std::size_t>(piece.n[2]);
    if (const pugi::xml_node pdata = node.child("PointData")) data_arrays(pd, pdata, false, points, type + "/Piece/PointData", piece.arrays);
    if (const pugi::xml_node cdata = node.child("CellData")) data_arrays(pd, cdata, true, cell_total(piece.n), type + "/Piece/CellData", piece.arrays);
    covered += static_cast<double>(points);
    pieces.push_back(std::move(piece));
  }
  if (pieces.empty()) d.fail(ptype + "/Piece", "missing (a parallel file names its pieces)");
  if (covered < total) d.fail(ptype, "the pieces do not cover the WholeExtent (" + std::to_string(static_cast<long long>(covered)) + " points for " + std::to_string(static_cast<long long>(total)) + ")");

  // The whole grid: every point and cell once. Points (or coordinates) and array values that two
  // pieces share must be equal; ghost flags (vtkGhostType) come from the piece that owns the
  // point or cell, and lose their duplicate bit: the joined grid holds no copies.
  const auto points = static_cast<std::size_t>(total);
  const std::size_t cells = cell_total(N);
  std::vector<Vec3> xyz(rectilinear ? 0 : points);
  std::array<std::vector<double>, 3> axis;
  std::array<std::vector<char>, 3> axis_set;
  for (std::size_t a = 0; a < 3; ++a) {
    axis[a].assign(static_cast<std::size_t>(N[a]), 0.0);
    axis_set[a].assign(static_cast<std::size_t>(N[a]), 0);
  }
  std::vector<char> point_set(points, 0), cell_set(cells, 0);
  std::vector<RawArray> arrays;
  for (const RawArray& r : pieces.front().arrays) {
    RawArray g = r;
    g.values.assign(r.components == 1 ? (r.cell ? cells : points) : 0, 0.0);
    arrays.push_back(std::move(g));
  }
  for (const StructuredPiece& piece : pieces) {
    const std::string field = type + "/Piece";
    const auto fail = [&](const std::string& f, const std::string& what) {
      throw InputError(piece.file + ": " + f + ": " + what);
    };
    // Local (i, j, k) -> whole index, for points and cells.
    const auto whole_point = [&](long long i, long long j, long long k) {
      return static_cast<std::size_t>((piece.lo[0] + i) + N[0] * ((piece.lo[1] + j) + static_cast<long long>(N[1]) * (piece.lo[2] + k)));
    };
    const auto whole_cell = [&](long long i, long long j, long long k) {
      return static_cast<std::size_t>((piece.lo[0] + i) + (N[0] - 1) * ((piece.lo[1] + j) + static_cast<long long>(N[1] - 1) * (piece.lo[2] + k)));
    };
    std::vector<std::size_t> pmap, cmap;
    for (long long k = 0; k < piece.n[2]; ++k)
      for (long long j = 0; j < piece.n[1]; ++j)
        for (long long i = 0; i < piece.n[0]; ++i) {
          pmap.push_back(whole_point(i, j, k));
          if (i + 1 < piece.n[0] && j + 1 < piece.n[1] && k + 1 < piece.n[2]) cmap.push_back(whole_cell(i, j, k));
        }
    if (rectilinear) {
      for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t i = 0; i < piece.axis[a].size(); ++i) {
          const auto g = static_cast<std::size_t>(piece.lo[a]) + i;
          if (axis_set[a][g] && !(axis[a][g] == piece.axis[a][i]))
            fail(field + "/Coordinates/DataArray[" + std::to_string(a) + "]", "coordinate " + std::to_string(i) +
                                                                                 " differs from the piece before that shares it");
          axis[a][g] = piece.axis[a][i];
          axis_set[a][g] = 1;
        }
    } else {
      for (std::size_t q = 0; q < pmap.size(); ++q) {
        if (point_set[pmap[q]] && !(xyz[pmap[q]] == piece.points[q]))
          fail(field + "/Points/DataArray", "point " + std::to_string(q) + " differs from the piece before that shares it");
        xyz[pmap[q]] = piece.points[q];
      }
    }
    for (RawArray& g : arrays) {
      const RawArray* match = nullptr;
      for (const RawArray& a : piece.arrays)
        if (a.name == g.name && a.cell == g.cell) match = &a;
      const std::string af = field + (g.cell ? "/CellData" : "/PointData");
      if (match == nullptr || match->components != g.components)
        fail(af, "array \"" + g.name + "\" is missing or has another component count in this piece");
      if (g.components != 1) continue;
      const std::vector<std::size_t>& map = g.cell ? cmap : pmap;
      const std::vector<char>& set = g.cell ? cell_set : point_set;
      for (std::size_t q = 0; q < map.size(); ++q) {
        const std::size_t at = map[q];
        const double v = match->values[q];
        if (is_ghost_array(g)) {
          // The owner's flags win over a copy's (a copy carries the duplicate bit).
          const bool copy = (static_cast<unsigned>(v) & kDuplicateBit) != 0;
          if (!set[at] || ((static_cast<unsigned>(g.values[at]) & kDuplicateBit) != 0 && !copy)) g.values[at] = v;
          continue;
        }
        if (set[at] && !same_value(g.values[at], v))
          fail(af + "/DataArray[" + g.name + "]", std::string(g.cell ? "cell " : "point ") + std::to_string(q) +
                                                       " is shared with a piece before and has another value there");
        g.values[at] = v;
      }
    }
    for (std::size_t at : pmap) point_set[at] = 1;
    for (std::size_t at : cmap) cell_set[at] = 1;
  }
  for (std::size_t i = 0; i < points; ++i)
    if (!point_set[i]) d.fail(ptype, "the pieces do not cover the WholeExtent (point " + std::to_string(i) + " missing)");
  for (std::size_t i = 0; i < cells; ++i)
    if (!cell_set[i]) d.fail(ptype, "the pieces do not cover the WholeExtent (cell " + std::to_string(i) + " missing)");
  for (RawArray& g : arrays)
    if (is_ghost_array(g))
      for (double& v : g.values) v = static_cast<double>(static_cast<unsigned>(v) & ~kDuplicateBit);
  RawMesh raw;
  if (rectilinear) {
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t i = 1; i < axis[a].size(); ++i)
        if (!(axis[a][i] > axis[a][i - 1]))
          d.fail(ptype, std::string("the pieces' coordinates do not increase along ") + "xyz"[a]);
    raw.points = rectilinear_points(axis);
  } else {
    raw.points = std::move(xyz);
  }
  raw.arrays = std::move(arrays);
  return assemble_structured(N, rectilinear, std::move(raw), source + " (" + std::to_string(pieces.size()) + " pieces)",
                             scalar, structured_fields(type));
}

std::string read_piece_file(const std::string& source, const std::string& type, const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(source + ": P" + type + "/Piece: the piece " + file + " does not exist");
  return json_source::read_text_file(file);
}

}  // namespace

CellMesh parse_pvts(std::string_view bytes, const std::string& source, const PieceFileLoader& load,
                    const ScalarChoice& scalar) {
  return parse_parallel_structured(bytes, source, load, false, scalar);
}

CellMesh parse_pvtr(std::string_view bytes, const std::string& source, const PieceFileLoader& load,
                    const ScalarChoice& scalar) {
  return parse_parallel_structured(bytes, source, load, true, scalar);
}

CellMesh read_pvts(const std::string& path, const ScalarChoice& scalar) {
  const auto load = [&](const std::string& file) { return read_piece_file(path, "StructuredGrid", file); };
  return parse_pvts(json_source::read_text_file(path), path, load, scalar);
}

CellMesh read_pvtr(const std::string& path, const ScalarChoice& scalar) {
  const auto load = [&](const std::string& file) { return read_piece_file(path, "RectilinearGrid", file); };
  return parse_pvtr(json_source::read_text_file(path), path, load, scalar);
}

}  // namespace rayint
