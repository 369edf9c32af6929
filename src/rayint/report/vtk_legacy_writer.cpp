// VTK legacy writer (see vtk_legacy_writer.hpp). Binary sections are big-endian, as VTK reads them.
#include "rayint/report/vtk_legacy_writer.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "rayint/core/atomic_file.hpp"

namespace rayint {
namespace {

template <typename T>
void put_big_endian(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<char>(bytes[sizeof(T) - 1 - i]));
}

void put_double(std::string& out, double x, bool binary) {
  if (binary) {
    put_big_endian(out, x);
  } else {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g ", x);
    out += buf;
  }
}

void put_int(std::string& out, std::int32_t x, bool binary) {
  if (binary) {
    put_big_endian(out, x);
  } else {
    out += std::to_string(x);
    out += ' ';
  }
}

}  // namespace

std::string encode_vtk_legacy(const TetMesh& mesh, const VtkWriteOptions& options) {
  const bool binary = options.encoding == VtkEncoding::binary;
  std::string title = options.title.substr(0, 255);
  for (char& c : title)
    if (c == '\n' || c == '\r') c = ' ';
  std::string out = "# vtk DataFile Version 3.0\n" + title + "\n" + (binary ? "BINARY\n" : "ASCII\n");
  out += "DATASET UNSTRUCTURED_GRID\n";
  out += "POINTS " + std::to_string(mesh.points.size()) + " double\n";
  for (const Vec3& p : mesh.points) {
    for (int k = 0; k < 3; ++k) put_double(out, p[k], binary);
    if (!binary) out.back() = '\n';
  }
  if (binary) out += '\n';
  out += "CELLS " + std::to_string(mesh.tets.size()) + " " + std::to_string(mesh.tets.size() * 5) + "\n";
  for (const auto& t : mesh.tets) {
    put_int(out, 4, binary);
    for (std::int32_t i : t) put_int(out, i, binary);
    if (!binary) out.back() = '\n';
  }
  if (binary) out += '\n';
  out += "CELL_TYPES " + std::to_string(mesh.tets.size()) + "\n";
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    put_int(out, 10, binary);
    if (!binary) out.back() = '\n';
  }
  if (binary) out += '\n';
  out += "POINT_DATA " + std::to_string(mesh.scalars.size()) + "\n";
  out += "SCALARS " + options.scalar_name + " double 1\nLOOKUP_TABLE default\n";
  for (double s : mesh.scalars) {
    put_double(out, s, binary);
    if (!binary) out.back() = '\n';
  }
  if (binary) out += '\n';
  return out;
}

void write_vtk_legacy(const std::string& path, const TetMesh& mesh, const VtkWriteOptions& options) {
  write_file_atomically(path, encode_vtk_legacy(mesh, options));
}

}  // namespace rayint
