// VTK legacy unstructured-grid reader (see vtk_legacy_reader.hpp for what is supported).
//
// The file is a sequence of keyword lines (text) each followed by its data: whitespace-separated
// numbers in ASCII files, raw big-endian values in BINARY files (starting right after the
// keyword line's '\n'). The reader walks it with one cursor; every array knows its size from its
// keyword line, so arrays the reader does not need are skipped, never guessed.
#include "rayint/input/vtk_legacy_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_assembly.hpp"
#include "rayint/input/vtk_image_blanking.hpp"

namespace rayint {
namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
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
  std::size_t remaining() const { return b_.size() - pos_; }

  // Fails unless `count` binary values of `type` (`width` bytes each) remain: checked before any
  // memory is taken for them, and the message says how many the file has.
  void binary_room(const std::string& section, const std::string& type, std::size_t count,
                   std::size_t width) const {
    if (count > remaining() / width)
      fail(section, "binary data truncated: need " + std::to_string(count) + " " + type +
                        " values, file has " + std::to_string(remaining() / width));
  }
  void binary_room(const std::string& section, const std::string& type, std::size_t count) const {
    binary_room(section, type, count, type_width(section, type));
  }

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
      binary_room(section, type, count, width);
      out.resize(count);
      decode_big_endian(type, width, out.data(), count);  // one type dispatch per array, not per value
      pos_ += count * width;
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
      // VTK reads an ASCII value of type float with `istream >> float` (vtkDataReader::Read(float*)),
      // which libstdc++ converts with strtof: the nearest float to the decimal text. Reading it as
      // a double instead keeps digits VTK does not see (the 2.8e-7 torus of issue 27).
      const double v = type == "float" ? static_cast<double>(std::strtof(tok.c_str(), &stop))
                                       : std::strtod(tok.c_str(), &stop);
      if (stop == tok.c_str() || *stop != '\0')
        fail(section + "[" + std::to_string(i) + "]", "not a number: '" + tok.substr(0, 40) + "'");
      out.push_back(v);
    }
    return out;
  }

  // True when values() of this array would be integers that integers() reads without doubles:
  // a BINARY file's integer types up to int64 (unsigned 64-bit ones may exceed it).
  bool integer_type(const std::string& type) const {
    return type != "float" && type != "double" && type != "bit" && type != "unsigned_long" && type != "vtktypeuint64";
  }

  // values() of a BINARY array written straight into `out` (count doubles).
  void binary_values_into(const std::string& section, const std::string& type, std::size_t count, double* out) {
    const std::size_t width = type_width(section, type);
    binary_room(section, type, count, width);
    decode_big_endian(type, width, out, count);
    pos_ += count * width;
  }

  // values() of a binary integer array (integer_type) as integers, decoded straight from the
  // big-endian bytes: the same numbers without an array of doubles between (issue 33), and
  // without an array of integers either: `use` gets a view (BigEndianView below: size() and
  // operator[], decoding each value where it lies in the file's bytes). An array of 8-byte
  // integers the size of the cell list was zero-filled and written first (4.2 MB and ~1,000 page
  // faults on the 105k-tet ball, ~7% of its load on the Zen 5 VM).
  template <class Use>
  void integers(const std::string& section, const std::string& type, std::size_t count, Use&& use) {
    const std::size_t width = type_width(section, type);
    binary_room(section, type, count, width);
    const auto* p = reinterpret_cast<const unsigned char*>(b_.data() + pos_);
    pos_ += count * width;
    if (type == "char" || type == "signed_char") use(BigEndianView<std::int8_t>{p, count});
    else if (type == "unsigned_char") use(BigEndianView<std::uint8_t>{p, count});
    else if (type == "short") use(BigEndianView<std::int16_t>{p, count});
    else if (type == "unsigned_short") use(BigEndianView<std::uint16_t>{p, count});
    else if (type == "int") use(BigEndianView<std::int32_t>{p, count});
    else if (type == "unsigned_int") use(BigEndianView<std::uint32_t>{p, count});
    else use(BigEndianView<std::int64_t>{p, count});  // long, vtktypeint64, vtkIdType (integer_type: no unsigned 64-bit)
  }

  // `count` big-endian integers of type T at p, read as long long on access.
  template <class T>
  struct BigEndianView {
    const unsigned char* p;
    std::size_t count;
    std::size_t size() const { return count; }
    long long operator[](std::size_t i) const {
      std::uint64_t bits = 0;
      for (std::size_t b = 0; b < sizeof(T); ++b) bits = (bits << 8) | p[i * sizeof(T) + b];
      using U = std::make_unsigned_t<T>;
      return static_cast<long long>(static_cast<T>(static_cast<U>(bits)));
    }
  };

 private:
  void skip_space() {
    while (pos_ < b_.size() && std::isspace(static_cast<unsigned char>(b_[pos_]))) ++pos_;
  }

  std::size_t type_width(const std::string& section, const std::string& type) const {
    const std::string t = type;
    // signed_char: VTK_SIGNED_CHAR as vtkDataWriter names it (e.g. ParaView's vtkValidPointMask).
    if (t == "unsigned_char" || t == "char" || t == "signed_char" || t == "bit") {
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

  // `count` big-endian values of `type` (width bytes each) from the cursor, as doubles.
  template <typename T>
  static void decode_as(const unsigned char* p, std::size_t width, double* out, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i, p += width) {
      std::uint64_t bits = 0;
      for (std::size_t b = 0; b < width; ++b) bits = (bits << 8) | p[b];
      if constexpr (sizeof(T) == 8) {
        T v;
        std::memcpy(&v, &bits, 8);
        out[i] = static_cast<double>(v);
      } else {
        const auto narrow = static_cast<std::uint32_t>(bits);
        unsigned char le[sizeof(T)];
        for (std::size_t b = 0; b < sizeof(T); ++b) le[b] = static_cast<unsigned char>(narrow >> (8 * b));
        T v;
        std::memcpy(&v, le, sizeof(T));
        out[i] = static_cast<double>(v);
      }
    }
  }
  void decode_big_endian(const std::string& type, std::size_t width, double* out, std::size_t count) const {
    const auto* p = reinterpret_cast<const unsigned char*>(b_.data() + pos_);
    if (type == "float") decode_as<float>(p, width, out, count);
    else if (type == "double") decode_as<double>(p, width, out, count);
    else if (type == "char" || type == "signed_char") decode_as<std::int8_t>(p, width, out, count);
    else if (type == "unsigned_char") decode_as<std::uint8_t>(p, width, out, count);
    else if (type == "short") decode_as<std::int16_t>(p, width, out, count);
    else if (type == "unsigned_short") decode_as<std::uint16_t>(p, width, out, count);
    else if (type == "int") decode_as<std::int32_t>(p, width, out, count);
    else if (type == "unsigned_int") decode_as<std::uint32_t>(p, width, out, count);
    else if (type == "unsigned_long" || type == "vtktypeuint64") decode_as<std::uint64_t>(p, width, out, count);
    else decode_as<std::int64_t>(p, width, out, count);
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

// The section is named "<section>[i]" only when it fails (no string built per value).
long long as_index(const VtkCursor& c, const char* section, std::size_t i, double v) {
  if (!(v == std::floor(v)) || v < -2147483648.0 || v > 2147483647.0)
    c.fail(std::string(section) + "[" + std::to_string(i) + "]", "not an integer point index: " + std::to_string(v));
  return static_cast<long long>(v);
}

}  // namespace

namespace {

// Everything a legacy file holds that rayint uses, for an unstructured grid or an image.
struct LegacyDataset {
  std::string kind;  // "UNSTRUCTURED_GRID" or "STRUCTURED_POINTS"
  RawMesh raw;
  bool have_points = false, have_cells = false, have_types = false;
  std::array<long long, 3> dims{};
  std::array<double, 3> origin{0, 0, 0}, spacing{1, 1, 1};
  bool have_dims = false;
};

// `want`: the dataset the caller reads ("UNSTRUCTURED_GRID" or "STRUCTURED_POINTS"); the other
// one is refused at its DATASET line, saying what it is.
LegacyDataset parse_legacy(VtkCursor& c, const std::string& want) {
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
    c.fail("DATASET", "expected 'DATASET UNSTRUCTURED_GRID' or 'DATASET STRUCTURED_POINTS'");
  LegacyDataset d;
  d.kind = upper(ds[1]);
  if (d.kind != "UNSTRUCTURED_GRID" && d.kind != "STRUCTURED_POINTS")
    c.fail("DATASET", "dataset " + ds[1].substr(0, 40) +
                          " is not read; only UNSTRUCTURED_GRID (a mesh) and STRUCTURED_POINTS (an image)");
  if (d.kind != want)
    c.fail("DATASET", d.kind == "STRUCTURED_POINTS"
                          ? "STRUCTURED_POINTS is image data, not a mesh: give it to a scene as \"grid_file\""
                          : "UNSTRUCTURED_GRID is a mesh, not an image: use it as a mesh case's \"mesh_file\"");
  RawMesh& raw = d.raw;
  // Cells go straight into raw.offsets / raw.connectivity (no vector per cell: issue 33).
  std::size_t n_cells_read = 0;
  std::size_t attribute_count = 0;  // tuples of the current POINT_DATA / CELL_DATA block
  bool in_point_data = false, in_data = false;
  const auto add_array = [&](const std::string& name, std::size_t comps, bool active, std::vector<double> values) {
    RawArray a;
    a.name = name;
    a.cell = !in_point_data;
    a.components = comps;
    a.active = active;
    a.values = std::move(values);
    raw.arrays.push_back(std::move(a));
  };
  while (!c.at_end()) {
    const std::vector<std::string> w = c.keyword_line("keyword");
    if (w.empty()) continue;
    const std::string key = upper(w[0]);
    if (key == "POINTS" && d.kind == "UNSTRUCTURED_GRID") {
      need_words(c, w, 3, "POINTS n type");
      const std::size_t n = count_of(c, "POINTS", w[1]);
      if (binary) {  // decoded into the points themselves (Vec3: three packed doubles)
        static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 holds three doubles, unpadded");
        c.binary_room("POINTS", w[2], 3 * n);  // before the points take memory
        raw.points.resize(n);
        c.binary_values_into("POINTS", w[2], 3 * n, raw.points.empty() ? nullptr : raw.points.front().data());
      } else {
        const std::vector<double> xyz = c.values("POINTS", w[2], 3 * n, false);
        raw.points.resize(n);
        for (std::size_t i = 0; i < n; ++i) raw.points[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
      }
      d.have_points = true;
    } else if (key == "DIMENSIONS" && d.kind == "STRUCTURED_POINTS") {
      need_words(c, w, 4, "DIMENSIONS nx ny nz");
      for (std::size_t a = 0; a < 3; ++a) d.dims[a] = static_cast<long long>(count_of(c, "DIMENSIONS", w[a + 1]));
      d.have_dims = true;
    } else if ((key == "ORIGIN" || key == "SPACING" || key == "ASPECT_RATIO") && d.kind == "STRUCTURED_POINTS") {
      need_words(c, w, 4, key + " x y z");
      std::array<double, 3>& into = key == "ORIGIN" ? d.origin : d.spacing;
      for (std::size_t a = 0; a < 3; ++a) {
        char* stop = nullptr;
        into[a] = std::strtod(w[a + 1].c_str(), &stop);
        if (stop == w[a + 1].c_str() || *stop != '\0' || !std::isfinite(into[a]))
          c.fail(key, "expected 3 finite numbers");
      }
    } else if (key == "CELLS" && d.kind == "UNSTRUCTURED_GRID") {
      need_words(c, w, 3, "CELLS n size");
      const std::size_t n = count_of(c, "CELLS", w[1]);
      const std::size_t size = count_of(c, "CELLS", w[2]);
      if (version >= 5.0) {  // CELLS n_offsets n_connectivity, then OFFSETS and CONNECTIVITY arrays
        const std::vector<std::string> wo = c.keyword_line("OFFSETS");
        if (wo.size() != 2 || upper(wo[0]) != "OFFSETS") c.fail("CELLS", "expected 'OFFSETS type' (file version 5.x)");
        // Binary integer arrays are read as integers (VtkCursor::integers), others as doubles.
        const auto fill = [&](const auto& offsets, const auto& conn) {
          if (n == 0) c.fail("OFFSETS", "empty (needs cells + 1 entries)");
          raw.offsets.assign(1, 0);
          raw.connectivity.clear();
          raw.offsets.reserve(n);
          raw.connectivity.reserve(size);
          prefault_capacity(raw.offsets);
          for (std::size_t i = 0; i + 1 < n; ++i) {
            const auto a = static_cast<double>(offsets[i]), b = static_cast<double>(offsets[i + 1]);
            if (!(a >= 0 && b >= a && b <= static_cast<double>(size)))
              c.fail("OFFSETS[" + std::to_string(i + 1) + "]", "offsets must increase within CONNECTIVITY");
            for (auto k = static_cast<std::size_t>(a); k < static_cast<std::size_t>(b); ++k)
              raw.connectivity.push_back(as_index(c, "CONNECTIVITY", k, static_cast<double>(conn[k])));
            raw.offsets.push_back(raw.connectivity.size());
          }
        };
        const auto read_connectivity = [&](const auto& offsets) {
          const std::vector<std::string> wc = c.keyword_line("CONNECTIVITY");
          if (wc.size() != 2 || upper(wc[0]) != "CONNECTIVITY")
            c.fail("CELLS", "expected 'CONNECTIVITY type' (file version 5.x)");
          if (binary && c.integer_type(wc[1])) c.integers("CONNECTIVITY", wc[1], size, [&](const auto& conn) { fill(offsets, conn); });
          else fill(offsets, c.values("CONNECTIVITY", wc[1], size, binary));
        };
        if (binary && c.integer_type(wo[1])) c.integers("OFFSETS", wo[1], n, read_connectivity);
        else read_connectivity(c.values("OFFSETS", wo[1], n, binary));
        n_cells_read = n - 1;
      } else {
        // One pass over the cell list; binary files' int32 values are read as integers.
        const auto fill = [&](const auto& rawc) {
          std::size_t k = 0;
          raw.offsets.assign(1, 0);
          raw.connectivity.clear();
          raw.offsets.reserve(n + 1);
          raw.connectivity.reserve(size);
          prefault_capacity(raw.offsets);
          for (std::size_t i = 0; i < n; ++i) {
            if (k >= rawc.size())
              c.fail("CELLS[" + std::to_string(i) + "]", "cell list ends early (size " + std::to_string(size) + ")");
            const auto m = static_cast<double>(rawc[k++]);
            if (!(m >= 0 && m <= static_cast<double>(rawc.size() - k)))  // m may be huge or NaN
              c.fail("CELLS[" + std::to_string(i) + "]", "point count " + format_number(m) + " overruns the cell list");
            for (auto j = static_cast<std::size_t>(m); j > 0; --j)
              raw.connectivity.push_back(as_index(c, "CELLS", i, static_cast<double>(rawc[k++])));
            raw.offsets.push_back(raw.connectivity.size());
          }
          if (k != rawc.size())
            c.fail("CELLS", "size " + std::to_string(size) + " does not match the cell list (" + std::to_string(k) + " used)");
        };
        if (binary) c.integers("CELLS", "int", size, fill);
        else fill(c.values("CELLS", "int", size, false));
        n_cells_read = n;
      }
      d.have_cells = true;
    } else if (key == "CELL_TYPES" && d.kind == "UNSTRUCTURED_GRID") {
      need_words(c, w, 2, "CELL_TYPES n");
      const std::size_t n = count_of(c, "CELL_TYPES", w[1]);
      const auto fill = [&](const auto& t) {
        raw.types.clear();
        raw.types.reserve(t.size());
        prefault_capacity(raw.types);
        for (std::size_t i = 0; i < t.size(); ++i) {
          const auto v = static_cast<double>(t[i]);
          if (!(v >= 0 && v <= 1e6 && v == std::floor(v)))
            c.fail("CELL_TYPES[" + std::to_string(i) + "]", "not a cell type: " + format_number(v));
          raw.types.push_back(static_cast<long long>(v));
        }
      };
      if (binary) c.integers("CELL_TYPES", "int", n, fill);
      else fill(c.values("CELL_TYPES", "int", n, false));
      d.have_types = true;
    } else if (key == "POINT_DATA" || key == "CELL_DATA") {
      need_words(c, w, 2, key + " n");
      attribute_count = count_of(c, key, w[1]);
      in_point_data = key == "POINT_DATA";
      in_data = true;
      if (in_point_data && d.have_points && attribute_count != raw.points.size())
        c.fail("POINT_DATA", std::to_string(attribute_count) + " scalars for " + std::to_string(raw.points.size()) +
                                 " points (need one per point)");
    } else if (!in_data && key != "FIELD" && key != "METADATA") {
      c.fail(w[0].substr(0, 40), "unknown keyword for DATASET " + d.kind);
    } else if (key == "SCALARS") {
      need_words(c, w, 3, "SCALARS name type [components]");
      const std::size_t comps = w.size() >= 4 ? count_of(c, "SCALARS", w[3]) : 1;
      // VTK always writes the LOOKUP_TABLE line after SCALARS; the reader requires it.
      const std::vector<std::string> lt = c.keyword_line("LOOKUP_TABLE");
      if (lt.empty() || upper(lt[0]) != "LOOKUP_TABLE")
        c.fail("SCALARS " + w[1], "expected 'LOOKUP_TABLE name' after SCALARS");
      add_array(w[1], comps, true,
                c.values(in_point_data ? "POINT_DATA" : "CELL_DATA", w[2], attribute_count * comps, binary));
    } else if (key == "LOOKUP_TABLE") {
      need_words(c, w, 3, "LOOKUP_TABLE name size");
      c.values("LOOKUP_TABLE", binary ? "unsigned_char" : "float", 4 * count_of(c, "LOOKUP_TABLE", w[2]), binary);
    } else if (key == "COLOR_SCALARS") {
      need_words(c, w, 3, "COLOR_SCALARS name n");
      const std::size_t comps = count_of(c, key, w[2]);
      c.values(key, binary ? "unsigned_char" : "float", attribute_count * comps, binary);
      add_array(w[1], comps, false, {});
    } else if (key == "VECTORS" || key == "NORMALS") {
      need_words(c, w, 3, key + " name type");
      c.values(key, w[2], 3 * attribute_count, binary);
      add_array(w[1], 3, false, {});
    } else if (key == "TENSORS") {
      need_words(c, w, 3, "TENSORS name type");
      c.values(key, w[2], 9 * attribute_count, binary);
      add_array(w[1], 9, false, {});
    } else if (key == "TEXTURE_COORDINATES") {
      need_words(c, w, 4, "TEXTURE_COORDINATES name dim type");
      const std::size_t comps = count_of(c, key, w[2]);
      c.values(key, w[3], comps * attribute_count, binary);
      add_array(w[1], comps, false, {});
    } else if (key == "GLOBAL_IDS" || key == "PEDIGREE_IDS") {
      need_words(c, w, 3, key + " name type");
      c.values(key, w[2], attribute_count, binary);
      add_array(w[1], 1, false, {});
      raw.arrays.back().name = w[1];
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
        const std::size_t comps = count_of(c, "FIELD", fa[1]), tuples = count_of(c, "FIELD", fa[2]);
        std::vector<double> data = c.values("FIELD " + fa[0], fa[3], comps * tuples, binary);
        // A FIELD block before any POINT_DATA / CELL_DATA is the dataset's field data (no
        // tuples per point or cell): not an attribute.
        if (in_data && tuples == attribute_count) add_array(fa[0], comps, false, std::move(data));
      }
    } else if (key == "METADATA") {
      while (c.more() && !c.line("METADATA").empty()) {}
    } else {
      c.fail(w[0].substr(0, 40), "unknown keyword");
    }
  }
  if (d.kind == "UNSTRUCTURED_GRID") {
    if (!d.have_points) c.fail("POINTS", "missing");
    if (!d.have_cells) c.fail("CELLS", "the file has no cells (an empty mesh: nothing to integrate)");
    if (!d.have_types) c.fail("CELL_TYPES", "missing");
    if (raw.types.size() != n_cells_read)
      c.fail("CELL_TYPES", std::to_string(raw.types.size()) + " types for " + std::to_string(n_cells_read) + " cells");
  } else if (!d.have_dims) {
    c.fail("DIMENSIONS", "missing");
  }
  return d;
}

// An UNSTRUCTURED_GRID's raw cells, with the assembly options the two mesh parsers take.
std::pair<RawMesh, AssemblyOptions> parse_unstructured(std::string_view bytes, const std::string& source,
                                                       const ScalarChoice& scalar) {
  VtkCursor c(bytes, source);
  LegacyDataset d = parse_legacy(c, "UNSTRUCTURED_GRID");
  AssemblyOptions o;
  o.scalar = scalar;
  return {std::move(d.raw), o};
}

}  // namespace

TetMesh parse_vtk_legacy(std::string_view bytes, const std::string& source,
                         const ScalarChoice& scalar) {
  auto [raw, options] = parse_unstructured(bytes, source, scalar);
  return assemble_tet_mesh(std::move(raw), source, options);
}

CellMesh parse_vtk_legacy_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar) {
  auto [raw, options] = parse_unstructured(bytes, source, scalar);
  return assemble_cell_mesh(std::move(raw), source, options);
}

CellMesh read_vtk_legacy_cells(const std::string& path, const ScalarChoice& scalar) {
  return parse_vtk_legacy_cells(json_source::read_big_file(path), path, scalar);
}

VoxelGrid parse_vtk_legacy_image(std::string_view bytes, const std::string& source,
                                 const std::string& scalar_name) {
  VtkCursor c(bytes, source);
  LegacyDataset d = parse_legacy(c, "STRUCTURED_POINTS");
  long long total = 1;
  std::array<int, 3> dims{};
  for (std::size_t a = 0; a < 3; ++a) {
    if (d.dims[a] < 2) c.fail("DIMENSIONS", "each axis needs at least 2 points (rayint's grids are 3-D)");
    total *= d.dims[a];
    if (d.dims[a] > (1LL << 28) || total > (1LL << 28)) c.fail("DIMENSIONS", "more than 2^28 points");
    dims[a] = static_cast<int>(d.dims[a]);
    if (!(d.spacing[a] > 0)) c.fail("SPACING", "must be > 0 on every axis");
  }
  const RawArray* chosen = nullptr;
  std::vector<MeshArrayInfo> infos;
  for (const RawArray& a : d.raw.arrays) infos.push_back({a.name, a.cell ? "cell" : "point", static_cast<long>(a.components), false});
  // Ghost flags and ParaView's valid-point mask are not the scalar (vtk_image_blanking.hpp).
  const auto bookkeeping = [](const std::string& name) { return name == "vtkGhostType" || name == "vtkValidPointMask"; };
  for (const RawArray& a : d.raw.arrays)
    if (!a.cell && (scalar_name.empty() ? a.components == 1 && !bookkeeping(a.name) : a.name == scalar_name)) {
      chosen = &a;
      break;
    }
  if (chosen == nullptr)
    c.fail("POINT_DATA", (scalar_name.empty() ? std::string("no one-component point array")
                                              : "no point array named " + field::quoted(scalar_name)) +
                             " (arrays: " + list_arrays(infos) + ")");
  if (chosen->components != 1)
    c.fail("POINT_DATA", "array " + field::quoted(chosen->name) + " has " + std::to_string(chosen->components) +
                             " components; the scalar needs 1");
  if (chosen->values.size() != static_cast<std::size_t>(total))
    c.fail("POINT_DATA", std::to_string(chosen->values.size()) + " values for " + std::to_string(total) + " points");
  for (std::size_t i = 0; i < chosen->values.size(); ++i)
    if (!std::isfinite(chosen->values[i]))
      c.fail("POINT_DATA[" + std::to_string(i) + "]", "not finite");
  VoxelGrid grid(dims, Vec3(d.origin[0], d.origin[1], d.origin[2]), Vec3(d.spacing[0], d.spacing[1], d.spacing[2]),
                 chosen->values);
  // Blanking as in a .vti (vtk_image_blanking.hpp): vtkGhostType of the points (HIDDENPOINT) and
  // of the cells (HIDDENCELL), which VTK's legacy writer puts in FIELD blocks.
  const auto cells = static_cast<std::size_t>((d.dims[0] - 1) * (d.dims[1] - 1) * (d.dims[2] - 1));
  std::vector<unsigned char> hidden_points, hidden_cells;
  for (const RawArray& a : d.raw.arrays) {
    if (a.name != "vtkGhostType") continue;
    const std::string f = std::string(a.cell ? "CELL_DATA" : "POINT_DATA") + "/vtkGhostType";
    const std::size_t n = a.cell ? cells : static_cast<std::size_t>(total);
    if (a.components != 1) c.fail(f, "needs 1 component");
    if (a.values.size() != n)
      c.fail(f, std::to_string(a.values.size()) + " values for " + std::to_string(n) + (a.cell ? " cells" : " points"));
    std::size_t bad = 0;
    (a.cell ? hidden_cells : hidden_points) = ghost_flags(a.values, a.cell ? kVtkHiddenCell : kVtkHiddenPoint, &bad);
    if (bad < n) c.fail(f, "value " + std::to_string(bad) + " is not a ghost flag (an integer in [0, 255])");
  }
  grid.set_hidden_cubes(hidden_cubes(dims, hidden_points, hidden_cells));
  return grid;
}

VoxelGrid read_vtk_legacy_image(const std::string& path, const std::string& scalar_name) {
  return parse_vtk_legacy_image(json_source::read_text_file(path), path, scalar_name);
}

TetMesh read_vtk_legacy(const std::string& path, const ScalarChoice& scalar) {
  return parse_vtk_legacy(json_source::read_big_file(path), path, scalar);
}

}  // namespace rayint
