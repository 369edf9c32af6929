// VTK legacy unstructured-grid reader (see vtk_legacy_reader.hpp for what is supported).
//
// The file is a sequence of keyword lines (text) each followed by its data: whitespace-separated
// numbers in ASCII files, raw big-endian values in BINARY files (starting right after the
// keyword line's '\n'). The reader walks it with one cursor; every array knows its size from its
// keyword line, so arrays the reader does not need are skipped, never guessed.
#include "rayint/input/vtk_legacy_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {
namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

const char* cell_type_name(long long type) {
  switch (type) {
    case 1: return "vertex";
    case 3: return "line";
    case 5: return "triangle";
    case 7: return "polygon";
    case 8: return "pixel";
    case 9: return "quad";
    case 10: return "tetra";
    case 11: return "voxel";
    case 12: return "hexahedron";
    case 13: return "wedge";
    case 14: return "pyramid";
    case 24: return "quadratic tetra";
    case 25: return "quadratic hexahedron";
    default: return "other";
  }
}

class VtkCursor {
 public:
  VtkCursor(std::string_view bytes, const std::string& source) : b_(bytes), source_(source) {}

  [[noreturn]] void fail(const std::string& section, const std::string& what) const {
    throw InputError(source_ + ": " + section + ": " + what);
  }

  bool at_end() {
    skip_space();
    return pos_ >= b_.size();
  }
  // True while bytes remain, without skipping blank lines (a METADATA block ends at one).
  bool more() const { return pos_ < b_.size(); }

  // One text line without its terminator ('\n' or "\r\n").
  std::string line(const std::string& section) {
    if (pos_ >= b_.size()) fail(section, "unexpected end of file");
    const std::size_t nl = b_.find('\n', pos_);
    const std::size_t end = nl == std::string_view::npos ? b_.size() : nl;
    std::string s(b_.substr(pos_, end - pos_));
    pos_ = nl == std::string_view::npos ? b_.size() : nl + 1;
    if (!s.empty() && s.back() == '\r') s.pop_back();
    return s;
  }

  // The next non-blank line split into whitespace-separated words.
  std::vector<std::string> keyword_line(const std::string& section) {
    skip_space();
    std::istringstream in(line(section));
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  }

  // `count` values of VTK type `type`, as doubles (ASCII or big-endian binary).
  std::vector<double> values(const std::string& section, const std::string& type, std::size_t count,
                             bool binary) {
    std::vector<double> out;
    const std::size_t width = type_width(section, type);
    if (binary) {
      if (count > (b_.size() - pos_) / width)
        fail(section, "binary data truncated: need " + std::to_string(count) + " " + type +
                          " values, file has " + std::to_string((b_.size() - pos_) / width));
      out.resize(count);
      for (std::size_t i = 0; i < count; ++i) out[i] = binary_value(type, width);
      return out;
    }
    out.reserve(std::min(count, (b_.size() - pos_) / 2 + 1));
    for (std::size_t i = 0; i < count; ++i) {
      skip_space();
      if (pos_ >= b_.size())
        fail(section, "expected " + std::to_string(count) + " values, file ends after " + std::to_string(i));
      std::size_t end = pos_;
      while (end < b_.size() && !std::isspace(static_cast<unsigned char>(b_[end]))) ++end;
      const std::string tok(b_.substr(pos_, end - pos_));
      pos_ = end;
      char* stop = nullptr;
      errno = 0;
      const double v = std::strtod(tok.c_str(), &stop);
      if (stop == tok.c_str() || *stop != '\0')
        fail(section + "[" + std::to_string(i) + "]", "not a number: '" + tok.substr(0, 40) + "'");
      out.push_back(v);
    }
    return out;
  }

 private:
  void skip_space() {
    while (pos_ < b_.size() && std::isspace(static_cast<unsigned char>(b_[pos_]))) ++pos_;
  }

  std::size_t type_width(const std::string& section, const std::string& type) const {
    const std::string t = type;
    if (t == "unsigned_char" || t == "char" || t == "bit") {
      if (t == "bit") fail(section, "data type 'bit' is not supported");
      return 1;
    }
    if (t == "short" || t == "unsigned_short") return 2;
    if (t == "int" || t == "unsigned_int" || t == "float") return 4;
    if (t == "long" || t == "unsigned_long" || t == "double" || t == "vtktypeint64" ||
        t == "vtktypeuint64" || t == "vtkIdType")
      return 8;
    fail(section, "unknown data type '" + type.substr(0, 40) + "'");
  }

  double binary_value(const std::string& type, std::size_t width) {
    unsigned char be[8];
    std::memcpy(be, b_.data() + pos_, width);
    pos_ += width;
    unsigned char le[8];
    for (std::size_t i = 0; i < width; ++i) le[i] = be[width - 1 - i];
    if (type == "float") { float f; std::memcpy(&f, le, 4); return static_cast<double>(f); }
    if (type == "double") { double d; std::memcpy(&d, le, 8); return d; }
    if (type == "char") { std::int8_t v; std::memcpy(&v, le, 1); return v; }
    if (type == "unsigned_char") return le[0];
    if (type == "short") { std::int16_t v; std::memcpy(&v, le, 2); return v; }
    if (type == "unsigned_short") { std::uint16_t v; std::memcpy(&v, le, 2); return v; }
    if (type == "int") { std::int32_t v; std::memcpy(&v, le, 4); return v; }
    if (type == "unsigned_int") { std::uint32_t v; std::memcpy(&v, le, 4); return v; }
    if (type == "unsigned_long" || type == "vtktypeuint64") {
      std::uint64_t v; std::memcpy(&v, le, 8); return static_cast<double>(v);
    }
    std::int64_t v; std::memcpy(&v, le, 8); return static_cast<double>(v);
  }

  std::string_view b_;
  std::string source_;
  std::size_t pos_ = 0;
};

std::size_t count_of(const VtkCursor& c, const std::string& section, const std::string& word) {
  char* stop = nullptr;
  errno = 0;
  const long long n = std::strtoll(word.c_str(), &stop, 10);
  if (stop == word.c_str() || *stop != '\0' || errno != 0 || n < 0 || n > (1LL << 40))
    c.fail(section, "expected a count, got '" + word.substr(0, 40) + "'");
  return static_cast<std::size_t>(n);
}

void need_words(const VtkCursor& c, const std::vector<std::string>& w, std::size_t n,
                const std::string& form) {
  if (w.size() < n) c.fail(w.empty() ? "(file)" : w[0], "expected '" + form + "'");
}

std::int32_t as_index(const VtkCursor& c, const std::string& section, double v) {
  if (!(v == std::floor(v)) || v < -2147483648.0 || v > 2147483647.0)
    c.fail(section, "not an integer point index: " + std::to_string(v));
  return static_cast<std::int32_t>(v);
}

}  // namespace

TetMesh parse_vtk_legacy(std::string_view bytes, const std::string& source,
                         const std::string& scalar_name) {
  VtkCursor c(bytes, source);
  const std::string magic = c.line("header");
  if (magic.rfind("# vtk DataFile Version", 0) != 0)
    c.fail("header", "not a VTK legacy file (first line must start with '# vtk DataFile Version')");
  const double version = std::atof(magic.c_str() + std::strlen("# vtk DataFile Version"));
  c.line("title");
  const std::vector<std::string> enc = c.keyword_line("encoding");
  if (enc.size() != 1 || (upper(enc[0]) != "ASCII" && upper(enc[0]) != "BINARY"))
    c.fail("encoding", "third line must be ASCII or BINARY");
  const bool binary = upper(enc[0]) == "BINARY";
  const std::vector<std::string> ds = c.keyword_line("DATASET");
  if (ds.size() != 2 || upper(ds[0]) != "DATASET")
    c.fail("DATASET", "expected 'DATASET UNSTRUCTURED_GRID'");
  if (upper(ds[1]) != "UNSTRUCTURED_GRID")
    c.fail("DATASET", "dataset " + ds[1].substr(0, 40) + " is not read; only UNSTRUCTURED_GRID");

  TetMesh mesh;
  bool have_points = false, have_cells = false, have_types = false, have_scalars = false;
  std::vector<double> field_scalars;  // the first one-component POINT_DATA FIELD array (meshio)
  std::vector<double> cell_types;
  std::vector<std::vector<std::int32_t>> cells;
  std::size_t attribute_count = 0;  // tuples of the current POINT_DATA / CELL_DATA block
  bool in_point_data = false;
  while (!c.at_end()) {
    const std::vector<std::string> w = c.keyword_line("keyword");
    if (w.empty()) continue;
    const std::string key = upper(w[0]);
    if (key == "POINTS") {
      need_words(c, w, 3, "POINTS n type");
      const std::size_t n = count_of(c, "POINTS", w[1]);
      const std::vector<double> xyz = c.values("POINTS", w[2], 3 * n, binary);
      mesh.points.resize(n);
      for (std::size_t i = 0; i < n; ++i) mesh.points[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      have_points = true;
    } else if (key == "CELLS") {
      need_words(c, w, 3, "CELLS n size");
      const std::size_t n = count_of(c, "CELLS", w[1]);
      const std::size_t size = count_of(c, "CELLS", w[2]);
      if (version >= 5.0) {  // CELLS n_offsets n_connectivity, then OFFSETS and CONNECTIVITY arrays
        const std::vector<std::string> wo = c.keyword_line("OFFSETS");
        if (wo.size() != 2 || upper(wo[0]) != "OFFSETS") c.fail("CELLS", "expected 'OFFSETS type' (file version 5.x)");
        const std::vector<double> offsets = c.values("OFFSETS", wo[1], n, binary);
        const std::vector<std::string> wc = c.keyword_line("CONNECTIVITY");
        if (wc.size() != 2 || upper(wc[0]) != "CONNECTIVITY")
          c.fail("CELLS", "expected 'CONNECTIVITY type' (file version 5.x)");
        const std::vector<double> conn = c.values("CONNECTIVITY", wc[1], size, binary);
        if (n == 0) c.fail("OFFSETS", "empty (needs cells + 1 entries)");
        for (std::size_t i = 0; i + 1 < n; ++i) {
          const double a = offsets[i], b = offsets[i + 1];
          if (!(a >= 0 && b >= a && b <= static_cast<double>(size)))
            c.fail("OFFSETS[" + std::to_string(i + 1) + "]", "offsets must increase within CONNECTIVITY");
          std::vector<std::int32_t> cell;
          for (auto k = static_cast<std::size_t>(a); k < static_cast<std::size_t>(b); ++k)
            cell.push_back(as_index(c, "CONNECTIVITY[" + std::to_string(k) + "]", conn[k]));
          cells.push_back(std::move(cell));
        }
      } else {
        const std::vector<double> raw = c.values("CELLS", "int", size, binary);
        std::size_t k = 0;
        for (std::size_t i = 0; i < n; ++i) {
          const std::string sec = "CELLS[" + std::to_string(i) + "]";
          if (k >= raw.size()) c.fail(sec, "cell list ends early (size " + std::to_string(size) + ")");
          const double m = raw[k++];
          if (!(m >= 0 && m <= static_cast<double>(raw.size() - k)))
            c.fail(sec, "point count " + std::to_string(static_cast<long long>(m)) + " overruns the cell list");
          std::vector<std::int32_t> cell;
          for (auto j = static_cast<std::size_t>(m); j > 0; --j) cell.push_back(as_index(c, sec, raw[k++]));
          cells.push_back(std::move(cell));
        }
        if (k != raw.size())
          c.fail("CELLS", "size " + std::to_string(size) + " does not match the cell list (" + std::to_string(k) + " used)");
      }
      have_cells = true;
    } else if (key == "CELL_TYPES") {
      need_words(c, w, 2, "CELL_TYPES n");
      cell_types = c.values("CELL_TYPES", "int", count_of(c, "CELL_TYPES", w[1]), binary);
      have_types = true;
    } else if (key == "POINT_DATA" || key == "CELL_DATA") {
      need_words(c, w, 2, key + " n");
      attribute_count = count_of(c, key, w[1]);
      in_point_data = key == "POINT_DATA";
      if (in_point_data && have_points && attribute_count != mesh.points.size())
        c.fail("POINT_DATA", std::to_string(attribute_count) + " scalars for " +
                                 std::to_string(mesh.points.size()) + " points (need one per point)");
    } else if (key == "SCALARS") {
      need_words(c, w, 3, "SCALARS name type [components]");
      const std::size_t comps = w.size() >= 4 ? count_of(c, "SCALARS", w[3]) : 1;
      // VTK always writes the LOOKUP_TABLE line after SCALARS; the reader requires it.
      const std::vector<std::string> lt = c.keyword_line("LOOKUP_TABLE");
      if (lt.empty() || upper(lt[0]) != "LOOKUP_TABLE")
        c.fail("SCALARS " + w[1], "expected 'LOOKUP_TABLE name' after SCALARS");
      const std::vector<double> data = c.values(in_point_data ? "POINT_DATA" : "CELL_DATA", w[2],
                                                attribute_count * comps, binary);
      const bool wanted = in_point_data && !have_scalars && (scalar_name.empty() || w[1] == scalar_name);
      if (wanted) {
        if (comps != 1)
          c.fail("POINT_DATA", "SCALARS " + w[1] + " has " + std::to_string(comps) + " components; need 1");
        mesh.scalars = data;
        have_scalars = true;
      }
    } else if (key == "LOOKUP_TABLE") {
      need_words(c, w, 3, "LOOKUP_TABLE name size");
      c.values("LOOKUP_TABLE", binary ? "unsigned_char" : "float", 4 * count_of(c, "LOOKUP_TABLE", w[2]), binary);
    } else if (key == "COLOR_SCALARS") {
      need_words(c, w, 3, "COLOR_SCALARS name n");
      c.values(key, binary ? "unsigned_char" : "float", attribute_count * count_of(c, key, w[2]), binary);
    } else if (key == "VECTORS" || key == "NORMALS") {
      need_words(c, w, 3, key + " name type");
      c.values(key, w[2], 3 * attribute_count, binary);
    } else if (key == "TENSORS") {
      need_words(c, w, 3, "TENSORS name type");
      c.values(key, w[2], 9 * attribute_count, binary);
    } else if (key == "TEXTURE_COORDINATES") {
      need_words(c, w, 4, "TEXTURE_COORDINATES name dim type");
      c.values(key, w[3], count_of(c, key, w[2]) * attribute_count, binary);
    } else if (key == "FIELD") {
      need_words(c, w, 3, "FIELD name n_arrays");
      const std::size_t arrays = count_of(c, "FIELD", w[2]);
      for (std::size_t a = 0; a < arrays; ++a) {
        std::vector<std::string> fa = c.keyword_line("FIELD");
        if (!fa.empty() && upper(fa[0]) == "METADATA") {  // 5.x: metadata block inside FIELD
          while (c.more() && !c.line("METADATA").empty()) {}
          fa = c.keyword_line("FIELD");
        }
        need_words(c, fa, 4, "arrayName components tuples type");
        const std::size_t n = count_of(c, "FIELD", fa[1]) * count_of(c, "FIELD", fa[2]);
        const std::vector<double> data = c.values("FIELD " + fa[0], fa[3], n, binary);
        if (in_point_data && !have_scalars && !scalar_name.empty() && fa[0] == scalar_name &&
            count_of(c, "FIELD", fa[1]) == 1) {
          mesh.scalars = data;
          have_scalars = true;
        }
        // meshio writes point data as FIELD arrays only: without a name, the first one-component
        // FIELD array of POINT_DATA stands in when the file has no SCALARS array at all.
        if (in_point_data && scalar_name.empty() && field_scalars.empty() &&
            count_of(c, "FIELD", fa[1]) == 1 && data.size() == attribute_count)
          field_scalars = data;
      }
    } else if (key == "METADATA") {
      while (c.more() && !c.line("METADATA").empty()) {}
    } else {
      c.fail(w[0].substr(0, 40), "unknown keyword");
    }
  }
  if (!have_points) c.fail("POINTS", "missing");
  if (!have_cells) c.fail("CELLS", "missing");
  if (!have_types) c.fail("CELL_TYPES", "missing");
  if (!have_scalars && !field_scalars.empty()) {
    mesh.scalars = field_scalars;
    have_scalars = true;
  }
  if (!have_scalars)
    c.fail("POINT_DATA", scalar_name.empty() ? "no SCALARS array (one scalar per point is required)"
                                             : "no SCALARS array named '" + scalar_name + "'");
  if (cell_types.size() != cells.size())
    c.fail("CELL_TYPES", std::to_string(cell_types.size()) + " types for " + std::to_string(cells.size()) + " cells");
  mesh.tets.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto type = static_cast<long long>(cell_types[i]);
    if (type != 10)
      c.fail("CELL_TYPES[" + std::to_string(i) + "]",
             "cell type " + std::to_string(type) + " (" + cell_type_name(type) +
                 ") is not read; only linear tetrahedra (type 10)");
    if (cells[i].size() != 4)
      c.fail("CELLS[" + std::to_string(i) + "]",
             "a tetrahedron needs 4 points, got " + std::to_string(cells[i].size()));
    std::copy(cells[i].begin(), cells[i].end(), mesh.tets[i].begin());
  }
  validate_tet_mesh_structure(mesh, source, MeshFieldNames{"POINTS", "POINT_DATA", "CELLS"});
  return mesh;
}

TetMesh read_vtk_legacy(const std::string& path, const std::string& scalar_name) {
  return parse_vtk_legacy(json_source::read_text_file(path), path, scalar_name);
}

}  // namespace rayint
