// PFM, OpenEXR and NumPy images in and out (see float_image.hpp for the conventions).
#include "rayint/render/float_image.hpp"

#include "rayint/render/npy_array.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <sys/stat.h>

#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/limits.hpp"

namespace rayint {
namespace {

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InputError(field::one_line(source + ": " + what));
}

void check_size(long long w, long long h, const std::string& source, const char* format) {
  if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
    fail(source, std::string(format) + ": image size " + std::to_string(w) + " x " +
                     std::to_string(h) + " outside 1.." + std::to_string(kMaxImageSide));
}

bool host_little_endian() {
  const std::uint16_t one = 1;
  unsigned char b = 0;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

template <class T>
T load(const char* p, bool little) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (little != host_little_endian()) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

template <class T>
void store(std::string& out, T v) {  // little-endian
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (!host_little_endian()) std::reverse(b, b + sizeof(T));
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// --- OpenEXR streams over memory, so writes are atomic and reads can be fuzzed ---

class MemoryOStream : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const std::size_t end = pos_ + static_cast<std::size_t>(n);
    if (end > data_.size()) data_.resize(end);
    std::memcpy(&data_[pos_], c, static_cast<std::size_t>(n));
    pos_ = end;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<std::size_t>(pos); }
  const std::string& data() const { return data_; }

 private:
  std::string data_;
  std::size_t pos_ = 0;
};

class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(std::string_view bytes, const std::string& name)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ > bytes_.size() || static_cast<std::size_t>(n) > bytes_.size() - pos_)
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = static_cast<std::size_t>(std::min<uint64_t>(pos, bytes_.size() + 1)); }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

// --- NumPy header: a Python dict literal with 'descr', 'fortran_order' and 'shape' ---

std::string npy_value(const std::string& header, const std::string& key, const std::string& source) {
  const std::string quoted = "'" + key + "'";
  const auto k = header.find(quoted);
  if (k == std::string::npos) fail(source, "npy header: no '" + key + "'");
  auto p = header.find(':', k + quoted.size());
  if (p == std::string::npos) fail(source, "npy header: no value for '" + key + "'");
  ++p;
  while (p < header.size() && header[p] == ' ') ++p;
  if (p >= header.size()) fail(source, "npy header: no value for '" + key + "'");
  if (header[p] == '\'') {
    const auto e = header.find('\'', p + 1);
    if (e == std::string::npos) fail(source, "npy header: unterminated '" + key + "'");
    return header.substr(p + 1, e - p - 1);
  }
  if (header[p] == '(') {
    const auto e = header.find(')', p);
    if (e == std::string::npos) fail(source, "npy header: unterminated '" + key + "'");
    return header.substr(p, e - p + 1);
  }
  auto e = p;
  while (e < header.size() && header[e] != ',' && header[e] != '}') ++e;
  std::string v = header.substr(p, e - p);
  while (!v.empty() && v.back() == ' ') v.pop_back();
  return v;
}

std::vector<long long> npy_shape(const std::string& tuple, const std::string& source) {
  std::vector<long long> dims;
  std::size_t i = 1;  // after '('
  while (i < tuple.size()) {
    while (i < tuple.size() && (tuple[i] == ' ' || tuple[i] == ',')) ++i;
    if (i >= tuple.size() || tuple[i] == ')') break;
    if (!std::isdigit(static_cast<unsigned char>(tuple[i])))
      fail(source, "npy header: 'shape' is not a tuple of sizes: " + tuple);
    long long v = 0;
    while (i < tuple.size() && std::isdigit(static_cast<unsigned char>(tuple[i]))) {
      v = v * 10 + (tuple[i] - '0');
      if (v > (1LL << 40)) fail(source, "npy header: 'shape' entry too large");
      ++i;
    }
    dims.push_back(v);
    if (dims.size() > 8) fail(source, "npy header: 'shape' has too many dimensions");
  }
  return dims;
}

}  // namespace

ImageFormat image_format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "png") return ImageFormat::png;
  if (ext == "pfm") return ImageFormat::pfm;
  if (ext == "exr") return ImageFormat::exr;
  if (ext == "npy") return ImageFormat::npy;
  fail(path, "unknown image extension \"." + ext + "\" (expected .png, .pfm, .exr or .npy)");
}

// ---------------------------------------------------------------- PFM

std::string encode_pfm(const Image& image) {
  if (image.width < 1 || image.height < 1) throw std::runtime_error("encode_pfm: empty image");
  std::string out = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  out.reserve(out.size() + image.pixels.size() * 12);
  for (int y = image.height - 1; y >= 0; --y)  // PFM: bottom row first
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) store<float>(out, static_cast<float>(image.at(x, y)[c]));
  return out;
}

namespace {

// The PFM header ("PF"/"Pf", width, height, scale, one whitespace): what decode_pfm and
// read_image_size need, from the file's first bytes.
struct PfmHeader {
  long long w = 0, h = 0;
  int channels = 3;
  double scale = 0.0;
  std::size_t data = 0;  // offset of the first pixel
};

PfmHeader pfm_header(std::string_view bytes, const std::string& source) {
  std::size_t p = 0;
  auto skip_space = [&] {
    while (p < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[p]))) ++p;
  };
  auto token = [&]() {
    skip_space();
    const std::size_t s = p;
    while (p < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[p])) && p - s < 64) ++p;
    return std::string(bytes.substr(s, p - s));
  };
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f'))
    fail(source, "pfm: not a PFM file (expected \"PF\" or \"Pf\")");
  const int channels = bytes[1] == 'F' ? 3 : 1;
  p = 2;
  long long w = 0, h = 0;
  double scale = 0.0;
  try {
    std::size_t used = 0;
    const std::string ws = token(), hs = token(), ss = token();
    w = std::stoll(ws, &used);
    if (used != ws.size()) throw std::invalid_argument(ws);
    h = std::stoll(hs, &used);
    if (used != hs.size()) throw std::invalid_argument(hs);
    scale = std::stod(ss, &used);
    if (used != ss.size()) throw std::invalid_argument(ss);
  } catch (const std::exception&) {
    fail(source, "pfm: header is not \"width height scale\"");
  }
  if (!std::isfinite(scale) || scale == 0.0) fail(source, "pfm: scale must be finite and non-zero");
  check_size(w, h, source, "pfm");
  if (p >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[p])))
    fail(source, "pfm: no whitespace after the header");
  ++p;  // exactly one whitespace character before the data
  return {w, h, channels, scale, p};
}

}  // namespace

Image decode_pfm(std::string_view bytes, const std::string& source) {
  const PfmHeader hd = pfm_header(bytes, source);
  const long long w = hd.w, h = hd.h;
  const int channels = hd.channels;
  const double scale = hd.scale;
  const std::size_t p = hd.data;
  const bool little = scale < 0.0;
  const std::size_t need = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * channels * 4;
  if (bytes.size() - p < need)
    fail(source, "pfm: " + std::to_string(bytes.size() - p) + " bytes of data, " +
                     std::to_string(need) + " needed for " + std::to_string(w) + " x " +
                     std::to_string(h));
  Image image(static_cast<int>(w), static_cast<int>(h));
  const char* d = bytes.data() + p;
  for (int row = 0; row < image.height; ++row) {
    const int y = image.height - 1 - row;
    for (int x = 0; x < image.width; ++x) {
      Rgb& px = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const int src = channels == 3 ? c : 0;
        px[c] = load<float>(d + ((static_cast<std::size_t>(row) * image.width + x) * channels + src) * 4, little);
      }
    }
  }
  return image;
}

// ---------------------------------------------------------------- OpenEXR

std::string encode_exr(const Image& image) {
  if (image.width < 1 || image.height < 1) throw std::runtime_error("encode_exr: empty image");
  const std::size_t n = image.pixels.size();
  std::vector<float> r(n), g(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = static_cast<float>(image.pixels[i][0]);
    g[i] = static_cast<float>(image.pixels[i][1]);
    b[i] = static_cast<float>(image.pixels[i][2]);
  }
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  Imf::FrameBuffer fb;
  const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(image.width);
  fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), xs, ys));
  fb.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), xs, ys));
  fb.insert("B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(b.data()), xs, ys));
  MemoryOStream stream;
  {
    Imf::OutputFile file(stream, header, 1);
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  }
  return stream.data();
}

namespace {

// The header's attribute sizes checked against the file before OpenEXR reads them. OpenEXR 3.1
// allocates an attribute's declared size before reading it (a string attribute: std::string of
// that size), so a 663-byte file declaring a 1.6 GB attribute took 1.2 GB of memory and 23 s under
// ASan (fuzz/exr_reader_fuzzer, 2026-12-03; tests/test_fuzz_regressions.cpp). Layout (OpenEXR
// file layout, "Header"): after the magic number and the 4-byte version field, attributes
// `name\0 type\0 int32 size, value[size]`, ended by an empty name; a multi-part file (version
// bit 12) has one such header per part, ended by an empty header.
void check_exr_header_sizes(std::string_view bytes, const std::string& source) {
  if (bytes.size() < 8) fail(source, "exr: truncated header");
  const bool multipart = (static_cast<unsigned char>(bytes[5]) & 0x10) != 0;
  std::size_t pos = 8;
  auto c_string = [&](const char* what) {
    const std::size_t end = bytes.find('\0', pos);
    if (end == std::string_view::npos || end - pos > 255)
      fail(source, std::string("exr: header: ") + what + " not terminated within 255 bytes");
    const std::size_t length = end - pos;
    pos = end + 1;
    return length;
  };
  for (;;) {
    std::size_t attributes = 0;
    while (c_string("attribute name") > 0) {
      c_string("attribute type");
      if (bytes.size() - pos < 4) fail(source, "exr: header: truncated attribute size");
      std::uint32_t size = 0;
      for (int k = 3; k >= 0; --k) size = (size << 8) | static_cast<unsigned char>(bytes[pos + static_cast<std::size_t>(k)]);
      pos += 4;
      if (size > bytes.size() - pos)
        fail(source, "exr: header: an attribute declares " + std::to_string(size) + " bytes, the file has " +
                         std::to_string(bytes.size() - pos) + " left");
      pos += size;
      ++attributes;
    }
    if (!multipart || attributes == 0) return;
  }
}

}  // namespace

ImageWithAlpha decode_exr_with_alpha(std::string_view bytes, const std::string& source) {
  // The magic number first: OpenEXR's own message for a non-EXR file is less direct.
  if (bytes.size() < 4 || static_cast<unsigned char>(bytes[0]) != 0x76 ||
      static_cast<unsigned char>(bytes[1]) != 0x2f || static_cast<unsigned char>(bytes[2]) != 0x31 ||
      static_cast<unsigned char>(bytes[3]) != 0x01)
    fail(source, "exr: not an OpenEXR file (bad magic number)");
  check_exr_header_sizes(bytes, source);
  try {
    MemoryIStream stream(bytes, source);
    Imf::InputFile file(stream, 1);
    const Imath::Box2i dw = file.header().dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    check_size(w, h, source, "exr");
    // A small compressed file can declare a huge image: its memory (the four float slices, the
    // decoded doubles) is checked against the limit before any of it is taken.
    limits::check(limits::kImageBytes,
                  static_cast<double>(bytes.size()) + static_cast<double>(w) * static_cast<double>(h) *
                                                          (sizeof(Rgb) + sizeof(double) + 4 * sizeof(float)),
                  source + ": (image): " + std::to_string(w) + " x " + std::to_string(h) + " pixels");
    const Imf::ChannelList& channels = file.header().channels();
    const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    const bool grey = channels.findChannel("Y") != nullptr;
    if (!rgb && !grey) fail(source, "exr: no R, G, B channels (nor Y)");
    for (auto it = channels.begin(); it != channels.end(); ++it)
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        fail(source, std::string("exr: channel ") + it.name() + " is subsampled");
    const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::vector<float> r(n, 0.0f), g(n, 0.0f), b(n, 0.0f), a;
    const bool has_alpha = channels.findChannel("A") != nullptr;
    if (has_alpha) a.assign(n, 0.0f);
    // Slices are addressed by absolute pixel coordinates: shift the base by the data window.
    const std::size_t xs = sizeof(float), ys = sizeof(float) * static_cast<std::size_t>(w);
    auto base = [&](std::vector<float>& v) {
      const std::ptrdiff_t offset = -(static_cast<std::ptrdiff_t>(dw.min.x) +
                                      static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(w));
      return reinterpret_cast<char*>(v.data()) + offset * static_cast<std::ptrdiff_t>(sizeof(float));
    };
    Imf::FrameBuffer fb;
    if (rgb) {
      fb.insert("R", Imf::Slice(Imf::FLOAT, base(r), xs, ys));
      fb.insert("G", Imf::Slice(Imf::FLOAT, base(g), xs, ys));
      fb.insert("B", Imf::Slice(Imf::FLOAT, base(b), xs, ys));
    } else {
      fb.insert("Y", Imf::Slice(Imf::FLOAT, base(r), xs, ys));
    }
    if (has_alpha) fb.insert("A", Imf::Slice(Imf::FLOAT, base(a), xs, ys));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    ImageWithAlpha out{Image(static_cast<int>(w), static_cast<int>(h)), {}};
    for (std::size_t i = 0; i < n; ++i)
      out.rgb.pixels[i] = rgb ? Rgb{r[i], g[i], b[i]} : Rgb{r[i], r[i], r[i]};
    out.alpha.assign(a.begin(), a.end());
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(source, std::string("exr: ") + e.what());
  }
}

// ---------------------------------------------------------------- NumPy

std::string encode_npy(const Image& image) {
  if (image.width < 1 || image.height < 1) throw std::runtime_error("encode_npy: empty image");
  static_assert(sizeof(Rgb) == 3 * sizeof(double), "Rgb pixels are three packed doubles");
  return encode_npy_array(image.pixels.front().data(), image.pixels.size() * 3,
                          {static_cast<std::size_t>(image.height), static_cast<std::size_t>(image.width), 3});
}

Image decode_exr(std::string_view bytes, const std::string& source) {
  return decode_exr_with_alpha(bytes, source).rgb;
}

namespace {

// The .npy header (magic, version, the dict with descr, fortran_order, shape): what
// decode_npy_with_alpha and read_image_size need, from the file's first bytes.
struct NpyHeader {
  std::vector<long long> shape;
  long long channels = 1;
  int item = 8;
  bool little = true;
  std::size_t data = 0;  // offset of the first value
};

NpyHeader npy_header(std::string_view bytes, const std::string& source) {
  if (bytes.size() < 10 || bytes.substr(0, 6) != std::string_view("\x93NUMPY", 6))
    fail(source, "npy: not a NumPy .npy file (bad magic)");
  const int major = static_cast<unsigned char>(bytes[6]);
  std::size_t header_len = 0, start = 0;
  if (major == 1) {
    header_len = load<std::uint16_t>(bytes.data() + 8, true);
    start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) fail(source, "npy: truncated header");
    header_len = load<std::uint32_t>(bytes.data() + 8, true);
    start = 12;
  } else {
    fail(source, "npy: unsupported format version " + std::to_string(major));
  }
  if (header_len > bytes.size() - start) fail(source, "npy: truncated header");
  const std::string header(bytes.substr(start, header_len));
  const std::string descr = npy_value(header, "descr", source);
  const std::string fortran = npy_value(header, "fortran_order", source);
  const std::vector<long long> shape = npy_shape(npy_value(header, "shape", source), source);
  int item = 0;
  bool little = true;
  if (descr == "<f8" || descr == ">f8") item = 8;
  else if (descr == "<f4" || descr == ">f4") item = 4;
  else fail(source, "npy: dtype '" + descr + "' not supported (float32 or float64 expected)");
  little = descr[0] == '<';
  if (fortran != "False") fail(source, "npy: fortran_order arrays are not supported");
  if (shape.size() < 2 || shape.size() > 3)
    fail(source, "npy: shape must be (height, width) or (height, width, channels)");
  const long long channels = shape.size() == 3 ? shape[2] : 1;
  if (channels != 1 && channels != 3 && channels != 4)
    fail(source, "npy: " + std::to_string(channels) + " channels (1, 3 or 4 expected)");
  check_size(shape[1], shape[0], source, "npy");
  return {shape, channels, item, little, start + header_len};
}

}  // namespace

ImageWithAlpha decode_npy_with_alpha(std::string_view bytes, const std::string& source) {
  const NpyHeader hd = npy_header(bytes, source);
  const std::vector<long long>& shape = hd.shape;
  const long long channels = hd.channels;
  const int item = hd.item;
  const bool little = hd.little;
  const std::size_t n = static_cast<std::size_t>(shape[0]) * static_cast<std::size_t>(shape[1]);
  const std::size_t need = n * static_cast<std::size_t>(channels) * static_cast<std::size_t>(item);
  const std::size_t data = hd.data;
  if (bytes.size() - data < need)
    fail(source, "npy: " + std::to_string(bytes.size() - data) + " bytes of data, " +
                     std::to_string(need) + " needed");
  ImageWithAlpha out{Image(static_cast<int>(shape[1]), static_cast<int>(shape[0])), {}};
  const char* d = bytes.data() + data;
  auto value = [&](std::size_t i, long long c) {
    const std::size_t k = (i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)) * item;
    return item == 8 ? load<double>(d + k, little) : static_cast<double>(load<float>(d + k, little));
  };
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.rgb.pixels[i][c] = value(i, channels == 1 ? 0 : c);
  if (channels == 4) {
    out.alpha.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.alpha[i] = value(i, 3);
  }
  return out;
}

Image decode_npy(std::string_view bytes, const std::string& source) {
  return decode_npy_with_alpha(bytes, source).rgb;
}

// ---------------------------------------------------------------- by extension

void write_image(const std::string& path, const Image& image, const PngOptions& png_options) {
  switch (image_format_of(path)) {
    case ImageFormat::png: write_png(path, image, png_options); return;
    case ImageFormat::pfm: write_file_atomically(path, encode_pfm(image)); return;
    case ImageFormat::exr: write_file_atomically(path, encode_exr(image)); return;
    case ImageFormat::npy: write_file_atomically(path, encode_npy(image)); return;
  }
}

ImageWithAlpha read_image_with_alpha(const std::string& path) {
  const ImageFormat format = image_format_of(path);
  if (format == ImageFormat::png) return {read_png(path), {}};
  // As read_png does for a PNG, the size comes from the header first and the memory it needs is
  // checked before any pixel is read: the file's bytes (under the input byte limit) plus the
  // decoded image (Rgb doubles, an alpha double, and OpenEXR's four float slices a pixel). A
  // .pfm or .npy header declaring 16384 x 16384 over a multi-GB file is refused in one line
  // here, not after the whole file has been read into memory.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, std::string("cannot open file (") + std::strerror(errno) + ")");
  if (!S_ISREG(st.st_mode))
    fail(path, "not a regular file (an image's header is read before its pixels)");
  limits::check(limits::kInputBytes, static_cast<double>(st.st_size), path + ": (file)");
  const ImageSize size = read_image_size(path);
  limits::check(limits::kImageBytes,
                static_cast<double>(st.st_size) + static_cast<double>(size.width) * size.height *
                                                      (sizeof(Rgb) + sizeof(double) + 4 * sizeof(float)),
                path + ": (image): " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                    " pixels");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  std::string bytes(static_cast<std::size_t>(st.st_size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (in.bad()) fail(path, "cannot read file");
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  switch (format) {
    case ImageFormat::pfm: return {decode_pfm(bytes, path), {}};
    case ImageFormat::exr: return decode_exr_with_alpha(bytes, path);
    default: return decode_npy_with_alpha(bytes, path);
  }
}

Image read_image(const std::string& path) { return read_image_with_alpha(path).rgb; }

ImageSize read_image_size(const std::string& path) {
  const ImageFormat format = image_format_of(path);
  if (format == ImageFormat::png) return read_png_size(path);
  if (format == ImageFormat::exr) {
    {  // the attribute sizes first (check_exr_header_sizes: OpenEXR allocates what they declare),
       // on the file's first 64 MiB, which hold the header of any real file
      std::ifstream in(path, std::ios::binary);
      if (!in) fail(path, "cannot open file");
      std::string head;
      char buf[1 << 16];
      while (head.size() < (std::size_t{64} << 20) && in.read(buf, sizeof buf).gcount() > 0)
        head.append(buf, static_cast<std::size_t>(in.gcount()));
      if (head.size() < 4 || static_cast<unsigned char>(head[0]) != 0x76 || static_cast<unsigned char>(head[1]) != 0x2f ||
          static_cast<unsigned char>(head[2]) != 0x31 || static_cast<unsigned char>(head[3]) != 0x01)
        fail(path, "exr: not an OpenEXR file (bad magic number)");
      check_exr_header_sizes(head, path);
    }
    try {
      const Imf::InputFile file(path.c_str());  // reads the header only
      const Imath::Box2i dw = file.header().dataWindow();
      const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
      const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
      check_size(w, h, path, "exr");
      return {static_cast<int>(w), static_cast<int>(h)};
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      fail(path, std::string("exr: ") + e.what());
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  // The header is at the start: PFM's within a few hundred bytes; .npy's length is in its first
  // 12 bytes (a version-1 header is at most 65,535 bytes; larger ones are refused here).
  const auto prefix = [&](std::size_t n) {
    std::string bytes(n, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(n));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
  };
  if (format == ImageFormat::pfm) {
    const PfmHeader hd = pfm_header(prefix(4096), path);
    return {static_cast<int>(hd.w), static_cast<int>(hd.h)};
  }
  std::string bytes = prefix(12);
  if (bytes.size() >= 12 && bytes.substr(0, 6) == std::string("\x93NUMPY", 6)) {
    const int major = static_cast<unsigned char>(bytes[6]);
    const std::size_t len = major == 1 ? load<std::uint16_t>(bytes.data() + 8, true) + 10u
                                       : load<std::uint32_t>(bytes.data() + 8, true) + 12u;
    if (len > (1u << 20)) fail(path, "npy: header of " + std::to_string(len) + " bytes (at most 1 MiB)");
    bytes += prefix(len - bytes.size());
  }
  const NpyHeader hd = npy_header(bytes, path);
  return {static_cast<int>(hd.shape[1]), static_cast<int>(hd.shape[0])};
}

}  // namespace rayint
