// The VTK XML DataArray decoder (see vtk_xml_data_array.hpp for the layout it reads).
#include "rayint/input/vtk_xml_data_array.hpp"

#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <limits>

#include "rayint/core/error.hpp"

namespace rayint::vtk_xml {
namespace {

// The largest ratio of decompressed to compressed bytes a block can claim, per compressor, plus
// slack for a stream's header (a block claiming more is refused before anything is allocated):
//   zlib: deflate's largest expansion, 1032:1 (zlib.net, "Technical details");
//   LZ4:  255:1 (a run costs at least one length byte per 255 bytes: LZ4 block format);
//   LZMA: xz streams (vtkLZMADataCompressor: lzma_easy_buffer_encode): measured 6513:1 on 16 MiB of
//         zeros at preset 5 (Python's lzma, the same liblzma); 16384 leaves room above that.
constexpr std::uint64_t kInflateSlack = 64;
std::uint64_t max_ratio(Compressor c) {
  switch (c) {
    case Compressor::zlib: return 1032;
    case Compressor::lz4: return 256;
    case Compressor::lzma: return 16384;
    case Compressor::none: break;
  }
  return 1;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

std::string clip(std::string_view s) {
  std::string out(s.substr(0, 40));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return out;
}

struct TypeInfo {
  std::size_t width = 0;
  enum Kind { kSigned, kUnsigned, kFloat } kind = kFloat;
};

bool type_info(const std::string& name, TypeInfo& t) {
  struct Row { const char* name; std::size_t width; TypeInfo::Kind kind; };
  static const Row rows[] = {
      {"Int8", 1, TypeInfo::kSigned},    {"UInt8", 1, TypeInfo::kUnsigned},
      {"Int16", 2, TypeInfo::kSigned},   {"UInt16", 2, TypeInfo::kUnsigned},
      {"Int32", 4, TypeInfo::kSigned},   {"UInt32", 4, TypeInfo::kUnsigned},
      {"Int64", 8, TypeInfo::kSigned},   {"UInt64", 8, TypeInfo::kUnsigned},
      {"Float32", 4, TypeInfo::kFloat},  {"Float64", 8, TypeInfo::kFloat}};
  for (const Row& r : rows)
    if (name == r.name) {
      t.width = r.width;
      t.kind = r.kind;
      return true;
    }
  return false;
}

// A word of `width` bytes in the file's byte order.
std::uint64_t word(const unsigned char* p, std::size_t width, bool big_endian) {
  std::uint64_t v = 0;
  if (big_endian)
    for (std::size_t b = 0; b < width; ++b) v = (v << 8) | p[b];
  else
    for (std::size_t b = width; b > 0; --b) v = (v << 8) | p[b - 1];
  return v;
}

double to_double(std::uint64_t bits, const TypeInfo& t) {
  if (t.kind == TypeInfo::kFloat) {
    if (t.width == 4) {
      const auto b32 = static_cast<std::uint32_t>(bits);
      float f = 0.0F;
      std::memcpy(&f, &b32, sizeof f);
      return static_cast<double>(f);
    }
    double d = 0.0;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  if (t.kind == TypeInfo::kUnsigned) return static_cast<double>(bits);
  const unsigned shift = static_cast<unsigned>(64 - 8 * t.width);  // sign-extend
  return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
}

// Little-endian data on a little-endian host: each value read as its own type and converted, the
// values to_double(word(...)) gives (a float or an integer to double: exact or the same rounding),
// in a loop per type instead of per-byte assembly and a type switch per value (~2.5% of the 105k
// .vtu load; issue 33). False: a type not listed (none today), decoded by the general loop.
constexpr bool little_endian_host() { return __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__; }

template <class T>
void convert_values(const unsigned char* p, double* into, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, p + i * sizeof(T), sizeof(T));
    into[i] = static_cast<double>(v);
  }
}

// Integers of `width` bytes, signed or not.
template <bool Signed>
bool convert_integers(const unsigned char* p, std::size_t width, double* into, std::size_t n) {
  switch (width) {
    case 8: convert_values<std::conditional_t<Signed, std::int64_t, std::uint64_t>>(p, into, n); return true;
    case 4: convert_values<std::conditional_t<Signed, std::int32_t, std::uint32_t>>(p, into, n); return true;
    case 2: convert_values<std::conditional_t<Signed, std::int16_t, std::uint16_t>>(p, into, n); return true;
    case 1: convert_values<std::conditional_t<Signed, std::int8_t, std::uint8_t>>(p, into, n); return true;
    default: return false;
  }
}

bool convert_native(const unsigned char* p, const TypeInfo& t, double* into, std::size_t n) {
  switch (t.kind) {
    case TypeInfo::kFloat:
      if (t.width == 8) convert_values<double>(p, into, n);
      else if (t.width == 4) convert_values<float>(p, into, n);
      else return false;
      return true;
    case TypeInfo::kSigned: return convert_integers<true>(p, t.width, into, n);
    case TypeInfo::kUnsigned: return convert_integers<false>(p, t.width, into, n);
  }
  return false;
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// The bytes of one array: raw (a view of the payload from the array's offset) or base64 text,
// read as a concatenation of '='-padded chunks. take(n) checks before it allocates.
class ByteStream {
 public:
  ByteStream(std::string_view text, bool base64, const Document& doc, std::string field)
      : text_(text), base64_(base64), doc_(doc), field_(std::move(field)) {}

  // The next n bytes of raw (not base64) data, in place.
  std::string_view view(std::size_t n, const std::string& what) {
    if (n > available())
      doc_.fail(field_, what + " truncated: needs " + std::to_string(n) + " bytes, " +
                            std::to_string(available()) + " left");
    const std::string_view out = text_.substr(pos_, n);
    pos_ += n;
    return out;
  }

  std::string take(std::size_t n, const std::string& what) {
    if (n > available())
      doc_.fail(field_, what + " truncated: needs " + std::to_string(n) + " bytes, " +
                            std::to_string(available()) + " left");
    std::string out;
    out.reserve(n);
    if (!base64_) {
      out.assign(text_.substr(pos_, n));
      pos_ += n;
      return out;
    }
    while (out.size() < n) {
      if (pending_pos_ < pending_.size()) {
        const std::size_t k = std::min(n - out.size(), pending_.size() - pending_pos_);
        out.append(pending_, pending_pos_, k);
        pending_pos_ += k;
        continue;
      }
      decode_quartet(what);
    }
    return out;
  }

 private:
  std::size_t available() const {
    if (!base64_) return text_.size() - pos_;
    return (text_.size() - pos_) / 4 * 3 + 3 + (pending_.size() - pending_pos_);  // upper bound
  }

  void decode_quartet(const std::string& what) {
    int v[4];
    int n = 0, pad = 0;
    while (n < 4) {
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (pos_ >= text_.size())
        doc_.fail(field_, what + " truncated: the base64 text ends inside the data");
      const char c = text_[pos_++];
      if (c == '=' && n >= 2) {
        ++pad;
        v[n++] = 0;
        continue;
      }
      if (pad > 0 || (v[n] = base64_value(c)) < 0)
        doc_.fail(field_, "invalid base64 character '" + clip(std::string_view(&c, 1)) + "' at text offset " +
                              std::to_string(pos_ - 1));
      ++n;
    }
    const std::uint32_t bits = (static_cast<std::uint32_t>(v[0]) << 18) | (static_cast<std::uint32_t>(v[1]) << 12) |
                               (static_cast<std::uint32_t>(v[2]) << 6) | static_cast<std::uint32_t>(v[3]);
    pending_.clear();
    pending_pos_ = 0;
    pending_.push_back(static_cast<char>(bits >> 16));
    if (pad < 2) pending_.push_back(static_cast<char>((bits >> 8) & 0xff));
    if (pad < 1) pending_.push_back(static_cast<char>(bits & 0xff));
  }

  std::string_view text_;
  bool base64_;
  const Document& doc_;
  std::string field_;
  std::size_t pos_ = 0;
  std::string pending_;
  std::size_t pending_pos_ = 0;
};

// One LZ4 block (vtkLZ4DataCompressor: LZ4_compress_default, a raw block without a frame).
std::string lz4_block(const std::string& in, std::size_t out_size, const Document& doc, const std::string& field,
                      std::uint64_t block) {
  std::string out(out_size, '\0');
  if (in.size() > static_cast<std::size_t>(LZ4_MAX_INPUT_SIZE) || out_size > static_cast<std::size_t>(LZ4_MAX_INPUT_SIZE) * 256)
    doc.fail(field, "compressed block " + std::to_string(block) + ": too large for LZ4");
  const int got = LZ4_decompress_safe(in.data(), out.data(), static_cast<int>(in.size()), static_cast<int>(out_size));
  if (got < 0)
    doc.fail(field, "compressed block " + std::to_string(block) + ": bad LZ4 block");
  if (static_cast<std::size_t>(got) != out_size)
    doc.fail(field, "compressed block " + std::to_string(block) + ": decompresses to " + std::to_string(got) +
                        " bytes, the header says " + std::to_string(out_size));
  return out;
}

// One LZMA block (vtkLZMADataCompressor: an .xz stream from lzma_easy_buffer_encode).
std::string lzma_block(const std::string& in, std::size_t out_size, const Document& doc, const std::string& field,
                       std::uint64_t block) {
  std::string out(out_size, '\0');
  std::uint64_t memlimit = 1ULL << 28;  // 256 MiB of decoder state at most (presets 0-9 need <= 65 MiB)
  std::size_t in_pos = 0, out_pos = 0;
  const lzma_ret rc = lzma_stream_buffer_decode(&memlimit, 0, nullptr, reinterpret_cast<const std::uint8_t*>(in.data()),
                                                &in_pos, in.size(), reinterpret_cast<std::uint8_t*>(out.data()),
                                                &out_pos, out.size());
  const std::string where = "compressed block " + std::to_string(block) + ": ";
  if (rc == LZMA_BUF_ERROR)
    doc.fail(field, where + "the xz stream does not decompress to the header's " + std::to_string(out_size) +
                        " bytes (truncated or larger)");
  if (rc != LZMA_OK) doc.fail(field, where + "bad xz stream (liblzma error " + std::to_string(static_cast<int>(rc)) + ")");
  if (out_pos != out_size)
    doc.fail(field, where + "decompresses to " + std::to_string(out_pos) + " bytes, the header says " +
                        std::to_string(out_size));
  return out;
}

std::string inflate_block(const std::string& in, std::size_t out_size, const Document& doc,
                          const std::string& field, std::uint64_t block) {
  std::string out(out_size, '\0');
  z_stream z{};
  if (inflateInit(&z) != Z_OK) doc.fail(field, "zlib: cannot initialise");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  z.avail_in = static_cast<uInt>(in.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&z, Z_FINISH);
  const std::size_t produced = out.size() - z.avail_out;
  const std::string msg = z.msg != nullptr ? z.msg : "";
  inflateEnd(&z);
  const std::string where = "compressed block " + std::to_string(block) + ": ";
  if (rc == Z_STREAM_END && produced == out_size) return out;
  if (rc == Z_BUF_ERROR || rc == Z_OK)
    doc.fail(field, where + (z.avail_out == 0 ? "inflates to more than the header's " + std::to_string(out_size) + " bytes"
                                              : "zlib stream ends early (" + std::to_string(produced) + " of " +
                                                    std::to_string(out_size) + " bytes)"));
  if (rc == Z_STREAM_END)
    doc.fail(field, where + "inflates to " + std::to_string(produced) + " bytes, the header says " +
                        std::to_string(out_size));
  doc.fail(field, where + "bad zlib stream (" + (msg.empty() ? "error " + std::to_string(rc) : clip(msg)) + ")");
}

}  // namespace

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
    case 42: return "polyhedron";
    default: return "other";
  }
}

Document::Document(std::string_view bytes, std::string source, const std::string& type)
    : source_(std::move(source)) {
  // The raw AppendedData payload is not XML (it may hold '<' and '&'): cut it out first. It runs
  // from the '_' after <AppendedData ...> to the last </AppendedData>.
  const std::size_t open = bytes.find("<AppendedData");
  if (open == std::string_view::npos) {
    xml_.assign(bytes);
  } else {
    const std::size_t gt = bytes.find('>', open);
    const std::size_t underscore = gt == std::string_view::npos ? gt : bytes.find('_', gt);
    const std::size_t close = bytes.rfind("</AppendedData>");
    if (gt == std::string_view::npos || underscore == std::string_view::npos || close == std::string_view::npos ||
        close < underscore)
      fail("AppendedData", "expected '<AppendedData encoding=...>', '_', the data and '</AppendedData>'");
    for (std::size_t i = gt + 1; i < underscore; ++i)
      if (!is_space(bytes[i])) fail("AppendedData", "expected '_' before the data");
    xml_.assign(bytes.substr(0, gt + 1));
    xml_.append(bytes.substr(close));
    appended_ = bytes.substr(underscore + 1, close - underscore - 1);
    has_appended_ = true;
  }
  const pugi::xml_parse_result r = doc_.load_buffer(xml_.data(), xml_.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!r)
    fail("XML", std::string(r.description()) + " at byte " + std::to_string(r.offset));
  const pugi::xml_node root = doc_.child("VTKFile");
  if (!root) fail("VTKFile", "missing (not a VTK XML file)");
  const std::string file_type = root.attribute("type").as_string();
  if (file_type != type)
    fail("VTKFile", "type \"" + clip(file_type) + "\" is not read here; expected \"" + type + "\"");
  const std::string order = root.attribute("byte_order").as_string("LittleEndian");
  if (order != "LittleEndian" && order != "BigEndian")
    fail("VTKFile", "byte_order \"" + clip(order) + "\": expected LittleEndian or BigEndian");
  big_endian_ = order == "BigEndian";
  const std::string header = root.attribute("header_type").as_string("UInt32");
  if (header != "UInt32" && header != "UInt64")
    fail("VTKFile", "header_type \"" + clip(header) + "\": expected UInt32 or UInt64");
  header_bytes_ = header == "UInt64" ? 8 : 4;
  if (const pugi::xml_attribute c = root.attribute("compressor")) {
    const std::string comp = c.as_string();
    if (comp == "vtkZLibDataCompressor")
      compressor_ = Compressor::zlib;
    else if (comp == "vtkLZ4DataCompressor")
      compressor_ = Compressor::lz4;
    else if (comp == "vtkLZMADataCompressor")
      compressor_ = Compressor::lzma;
    else if (!comp.empty())
      fail("VTKFile", "compressor \"" + clip(comp) +
                          "\" is not read; only vtkZLibDataCompressor, vtkLZ4DataCompressor, vtkLZMADataCompressor");
  }
  if (has_appended_) {
    const pugi::xml_node a = root.child("AppendedData");
    const std::string enc = a.attribute("encoding").as_string();
    if (enc != "raw" && enc != "base64")
      fail("AppendedData", "encoding \"" + clip(enc) + "\": expected raw or base64");
    appended_base64_ = enc == "base64";
  }
  dataset_ = only_child(root, type.c_str(), "VTKFile");
}

void Document::fail(const std::string& field, const std::string& what) const {
  throw InputError(source_ + ": " + field + ": " + what);
}

pugi::xml_node Document::only_child(pugi::xml_node parent, const char* name, const std::string& field) const {
  pugi::xml_node found;
  for (pugi::xml_node c = parent.child(name); c; c = c.next_sibling(name)) {
    if (found) fail(field + "/" + name, "more than one (only single-piece files are read)");
    found = c;
  }
  if (!found) fail(field + "/" + name, "missing");
  return found;
}

long long Document::count_attribute(pugi::xml_node node, const char* name, const std::string& field,
                                    long long max) const {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) fail(field, std::string("missing attribute ") + name);
  const char* s = a.value();
  char* stop = nullptr;
  errno = 0;
  const long long v = std::strtoll(s, &stop, 10);
  while (stop != nullptr && is_space(*stop)) ++stop;
  if (stop == s || *stop != '\0' || errno != 0 || v < 0 || v > max)
    fail(field, std::string(name) + " = \"" + clip(s) + "\": expected an integer in [0, " + std::to_string(max) + "]");
  return v;
}

std::vector<double> Document::numbers_attribute(pugi::xml_node node, const char* name, const std::string& field,
                                                std::size_t n, const std::vector<double>& fallback) const {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) {
    if (!fallback.empty()) return fallback;
    fail(field, std::string("missing attribute ") + name);
  }
  std::vector<double> out;
  const char* p = a.value();
  while (true) {
    while (is_space(*p)) ++p;
    if (*p == '\0') break;
    char* stop = nullptr;
    const double v = std::strtod(p, &stop);
    if (stop == p || !std::isfinite(v) || out.size() == n)
      fail(field, std::string(name) + " = \"" + clip(a.value()) + "\": expected " + std::to_string(n) + " finite numbers");
    out.push_back(v);
    p = stop;
  }
  if (out.size() != n)
    fail(field, std::string(name) + " = \"" + clip(a.value()) + "\": expected " + std::to_string(n) + " numbers");
  return out;
}

std::size_t Document::components(pugi::xml_node array, const std::string& field) const {
  if (!array.attribute("NumberOfComponents")) return 1;
  const long long c = count_attribute(array, "NumberOfComponents", field, 1 << 16);
  if (c == 0) fail(field, "NumberOfComponents is 0");
  return static_cast<std::size_t>(c);
}

std::vector<double> Document::values(pugi::xml_node array, const std::string& field, std::size_t expected) const {
  std::vector<double> out;
  values_into(array, field, expected, [&] {
    out.resize(expected);
    return out.data();
  });
  return out;
}

void Document::values_into(pugi::xml_node array, const std::string& field, std::size_t expected,
                           const std::function<double*()>& buffer) const {
  TypeInfo t;
  const std::string type = array.attribute("type").as_string();
  if (!array.attribute("type")) fail(field, "missing attribute type");
  if (!type_info(type, t))
    fail(field, "type \"" + clip(type) + "\" is not read (Int8..UInt64, Float32, Float64)");
  const std::string format = array.attribute("format").as_string();
  std::vector<double> out;

  if (format == "ascii") {
    const char* p = array.child_value();
    out.reserve(std::min<std::size_t>(expected, std::strlen(p) / 2 + 1));
    while (true) {
      while (is_space(*p)) ++p;
      if (*p == '\0') break;
      if (out.size() == expected)
        fail(field, "more than the expected " + std::to_string(expected) + " values");
      char* stop = nullptr;
      errno = 0;
      double v = 0.0;
      if (t.kind == TypeInfo::kFloat) {
        // Float32 as VTK's XML parser reads it (istream >> float: strtof, the nearest float;
        // strtod then a cast to float could round twice).
        v = t.width == 4 ? static_cast<double>(std::strtof(p, &stop)) : std::strtod(p, &stop);
      } else if (t.kind == TypeInfo::kSigned) {
        const long long x = std::strtoll(p, &stop, 10);
        const long long lim = t.width == 8 ? std::numeric_limits<long long>::max() : (1LL << (8 * t.width - 1)) - 1;
        if (x > lim || x < -lim - 1) errno = ERANGE;
        v = static_cast<double>(x);
      } else {
        const unsigned long long x = *p == '-' ? 0 : std::strtoull(p, &stop, 10);
        if (*p == '-' || (t.width < 8 && x >> (8 * t.width) != 0)) errno = ERANGE;
        v = static_cast<double>(x);
      }
      if (stop == p || stop == nullptr || (*stop != '\0' && !is_space(*stop)) || (errno == ERANGE && t.kind != TypeInfo::kFloat))
        fail(field, "value " + std::to_string(out.size()) + ": not a " + type + ": '" + clip(std::string_view(p, std::strcspn(p, " \t\r\n"))) + "'");
      out.push_back(v);
      p = stop;
    }
    if (out.size() != expected)
      fail(field, "has " + std::to_string(out.size()) + " values, expected " + std::to_string(expected));
    std::copy(out.begin(), out.end(), buffer());
    return;
  }

  std::string_view text;
  bool base64 = true;
  if (format == "binary") {
    text = array.child_value();
  } else if (format == "appended") {
    if (!has_appended_) fail(field, "format=\"appended\" but the file has no AppendedData");
    const long long offset = count_attribute(array, "offset", field, std::numeric_limits<long long>::max());
    if (static_cast<unsigned long long>(offset) > appended_.size())
      fail(field, "offset " + std::to_string(offset) + " is beyond the AppendedData (" +
                      std::to_string(appended_.size()) + " bytes)");
    text = appended_.substr(static_cast<std::size_t>(offset));
    base64 = appended_base64_;
  } else {
    fail(field, "format \"" + clip(format) + "\": expected ascii, binary or appended");
  }

  if (expected > std::numeric_limits<std::size_t>::max() / 8) fail(field, "too many values");
  const std::uint64_t data_bytes = static_cast<std::uint64_t>(expected) * t.width;
  ByteStream in(text, base64, *this, field);
  const auto header_word = [&](const std::string& what) {
    const std::string h = in.take(header_bytes_, what);
    return word(reinterpret_cast<const unsigned char*>(h.data()), header_bytes_, big_endian_);
  };
  std::string data;       // decoded bytes (base64 or compressed)
  std::string_view bytes;  // the data: raw bytes in place, or `data`
  if (compressor_ == Compressor::none) {
    const std::uint64_t size = header_word("header");
    if (size != data_bytes)
      fail(field, "header says " + std::to_string(size) + " bytes, expected " + std::to_string(data_bytes) + " (" +
                      std::to_string(expected) + " " + type + ")");
    if (base64) data = in.take(static_cast<std::size_t>(size), "data");
    else bytes = in.view(static_cast<std::size_t>(size), "data");  // no copy of the payload (issue 33)
  } else {
    const std::uint64_t nblocks = header_word("compression header");
    const std::uint64_t block = header_word("compression header");
    const std::uint64_t last = header_word("compression header");
    if (nblocks > text.size() / header_bytes_ + 1)
      fail(field, "compression header: " + std::to_string(nblocks) + " blocks cannot fit in the file");
    if (last > block) fail(field, "compression header: last block size " + std::to_string(last) + " exceeds the block size " + std::to_string(block));
    // The blocks must inflate to exactly the expected bytes (checked without overflow).
    const std::uint64_t last_size = last == 0 ? block : last;
    const bool fits = nblocks == 0 ? data_bytes == 0
                                   : block != 0 && nblocks - 1 <= data_bytes / block &&
                                         last_size == data_bytes - (nblocks - 1) * block;
    if (!fits)
      fail(field, "compression header: " + std::to_string(nblocks) + " blocks of " + std::to_string(block) +
                      " bytes (last " + std::to_string(last) + ") do not hold the expected " +
                      std::to_string(data_bytes) + " bytes (" + std::to_string(expected) + " " + type + ")");
    const std::uint64_t total = data_bytes;
    std::vector<std::uint64_t> csize(static_cast<std::size_t>(nblocks));
    for (auto& c : csize) c = header_word("compression header");
    const std::uint64_t ratio = max_ratio(compressor_);
    data.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(total, text.size() * ratio)));
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      const std::uint64_t out_size = (b + 1 == nblocks && last != 0) ? last : block;
      const std::uint64_t c = csize[static_cast<std::size_t>(b)];
      if (c > text.size()) fail(field, "compressed block " + std::to_string(b) + ": size " + std::to_string(c) + " is beyond the file");
      if (out_size > c * ratio + kInflateSlack)
        fail(field, "compressed block " + std::to_string(b) + ": " + std::to_string(c) +
                        " bytes cannot inflate to " + std::to_string(out_size));
      const std::string packed = in.take(static_cast<std::size_t>(c), "compressed block " + std::to_string(b));
      const auto n = static_cast<std::size_t>(out_size);
      data += compressor_ == Compressor::zlib  ? inflate_block(packed, n, *this, field, b)
              : compressor_ == Compressor::lz4 ? lz4_block(packed, n, *this, field, b)
                                               : lzma_block(packed, n, *this, field, b);
    }
  }
  if (bytes.data() == nullptr) bytes = data;
  double* into = buffer();
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (!big_endian_ && little_endian_host() && convert_native(p, t, into, expected)) return;
  for (std::size_t i = 0; i < expected; ++i, p += t.width) into[i] = to_double(word(p, t.width, big_endian_), t);
}

}  // namespace rayint::vtk_xml
