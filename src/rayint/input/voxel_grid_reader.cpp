// Reading voxel grids: the strict schema walk of voxel_grid_reader.hpp, and the decoding of raw
// little-endian files (byte by byte, so the host's byte order does not matter).
#include "rayint/input/voxel_grid_reader.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/vtk_legacy_reader.hpp"
#include "rayint/input/vtk_xml_reader.hpp"

namespace rayint {

namespace {

using nlohmann::json;
using json_source::format_number;
using json_source::index_path;
using json_source::member_path;
using json_source::quoted;

std::string read_binary_file(const std::string& file, const JsonSchema& s,
                             const std::string& path) {
  return json_source::read_file_bytes(file, [&](const std::string& reason) {
    s.fail(path, "cannot read " + quoted(file) + " (" + reason + ")");
  });
}

std::uint64_t little_endian(const unsigned char* p, int size) {
  std::uint64_t v = 0;
  for (int b = size - 1; b >= 0; --b) v = (v << 8) | p[b];
  return v;
}

std::string point_name(std::size_t index, const std::array<int, 3>& dims) {
  const std::size_t nx = static_cast<std::size_t>(dims[0]), ny = static_cast<std::size_t>(dims[1]);
  return "value " + std::to_string(index) + " (i=" + std::to_string(index % nx) + ", j=" +
         std::to_string((index / nx) % ny) + ", k=" + std::to_string(index / (nx * ny)) + ")";
}

std::vector<double> decode_raw(const std::string& bytes, const std::string& type, std::size_t n,
                               const std::array<int, 3>& dims, const std::string& file,
                               const JsonSchema& s, const std::string& path) {
  const int size = type == "float64" ? 8 : type == "float32" ? 4 : type == "uint16" ? 2 : 1;
  const std::size_t expected = n * static_cast<std::size_t>(size);
  if (bytes.size() != expected)
    s.fail(path, quoted(file) + " has " + std::to_string(bytes.size()) + " bytes, expected " +
                     std::to_string(expected) + " (" + std::to_string(n) + " " + type + ")");
  std::vector<double> values(n);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::size_t i = 0; i < n; ++i, p += size) {
    const std::uint64_t bits = little_endian(p, size);
    double v = 0.0;
    if (type == "float64") {
      std::memcpy(&v, &bits, sizeof v);
    } else if (type == "float32") {
      const auto b32 = static_cast<std::uint32_t>(bits);
      float x = 0.0F;
      std::memcpy(&x, &b32, sizeof x);
      v = static_cast<double>(x);
    } else {
      v = static_cast<double>(bits);
    }
    if (!std::isfinite(v))
      s.fail(path, quoted(file) + ": " + point_name(i, dims) + " is not finite (" +
                       format_number(v) + ")");
    values[i] = v;
  }
  return values;
}

std::vector<double> json_values(const json& j, const JsonSchema& s, const std::string& path,
                                std::size_t n) {
  s.non_empty_array(j, path, " of numbers");
  if (j.size() != n)
    s.fail(path, "has " + std::to_string(j.size()) + " values, expected nx*ny*nz = " +
                     std::to_string(n));
  std::vector<double> values(n);
  for (std::size_t i = 0; i < n; ++i) values[i] = s.finite_number(j[i], index_path(path, i));
  return values;
}

}  // namespace

VoxelGrid parse_voxel_grid(const json& j, const JsonSchema& s, const std::string& path,
                           const std::string& base_dir) {
  s.require_object(j, path);
  s.check_fields(j, path, {"dims", "origin", "spacing", "values", "values_file", "value_type"});
  const std::string dims_path = member_path(path, "dims");
  const json& jd = s.required(j, path, "dims");
  s.array_of_size(jd, dims_path, 3, "an array of 3 point counts [nx, ny, nz]");
  std::array<int, 3> dims{};
  long long n = 1;
  for (std::size_t i = 0; i < 3; ++i) {
    dims[i] = static_cast<int>(s.integer(jd[i], index_path(dims_path, i), 2, kMaxGridPoints));
    n *= dims[i];
    if (n > kMaxGridPoints)
      s.fail(dims_path, "more than " + std::to_string(kMaxGridPoints) + " grid points");
  }
  const Vec3 origin = s.vec3(s.required(j, path, "origin"), member_path(path, "origin"));
  const std::string spacing_path = member_path(path, "spacing");
  const json& js = s.required(j, path, "spacing");
  s.array_of_size(js, spacing_path, 3, "an array of 3 numbers [dx, dy, dz]");
  Vec3 spacing;
  for (std::size_t i = 0; i < 3; ++i)
    spacing[static_cast<Eigen::Index>(i)] = s.positive(js[i], index_path(spacing_path, i));
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(origin[i] + (dims[i] - 1) * spacing[i]))
      s.fail(spacing_path, "the grid's extent overflows");

  const json* inline_values = s.optional(j, "values");
  const json* file_field = s.optional(j, "values_file");
  const json* type_field = s.optional(j, "value_type");
  const auto count = static_cast<std::size_t>(n);
  std::vector<double> values;
  if (inline_values && file_field)
    s.fail(member_path(path, "values_file"), "give either values or values_file, not both");
  if (inline_values) {
    if (type_field) s.fail(member_path(path, "value_type"), "only used with values_file");
    values = json_values(*inline_values, s, member_path(path, "values"), count);
  } else if (file_field) {
    const std::string file_path = member_path(path, "values_file");
    const std::string name = s.non_empty_string(*file_field, file_path);
    if (!type_field)
      s.fail(member_path(path, "value_type"),
             "missing required field (with values_file): float32, float64, uint8, uint16 or json");
    const std::string type_path = member_path(path, "value_type");
    const std::string type = s.string_value(*type_field, type_path);
    if (type != "float32" && type != "float64" && type != "uint8" && type != "uint16" &&
        type != "json")
      s.fail(type_path, "must be float32, float64, uint8, uint16 or json, got " + quoted(type));
    std::filesystem::path file(name);
    if (file.is_relative() && !base_dir.empty()) file = std::filesystem::path(base_dir) / file;
    const std::string bytes = read_binary_file(file.string(), s, file_path);
    if (type == "json") {
      const JsonSchema inner(file.string());
      values = json_values(json_source::parse(bytes, file.string()), inner, "", count);
    } else {
      values = decode_raw(bytes, type, count, dims, file.string(), s, file_path);
    }
  } else {
    s.fail(member_path(path, "values"), "missing required field (or give values_file)");
  }
  return VoxelGrid(dims, origin, spacing, std::move(values));
}

VoxelGrid parse_voxel_grid_text(std::string_view text, const std::string& source,
                                const std::string& base_dir) {
  const json root = json_source::parse(text, source);
  return parse_voxel_grid(root, JsonSchema(source), "", base_dir);
}

VoxelGrid read_voxel_grid_file(const std::string& path, const std::string& array) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".vti") return read_vti(path, array);    // VTK XML image data (input/vtk_xml_reader.hpp)
  if (ext == ".pvti") return read_pvti(path, array);  // its parallel pieces
  if (ext == ".vtk") return read_vtk_legacy_image(path, array);  // STRUCTURED_POINTS (vtk_legacy_reader.hpp)
  if (!array.empty())
    throw InputError(path + ": (root): \"array\" names an array of a VTK image (.vti, .pvti, .vtk); a JSON grid has one");
  const std::string text = json_source::read_text_file(path);
  return parse_voxel_grid_text(text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace rayint
