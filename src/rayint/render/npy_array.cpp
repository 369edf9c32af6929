#include "rayint/render/npy_array.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace rayint {

std::string encode_npy_array(const double* data, std::size_t count, const std::vector<std::size_t>& shape) {
  std::size_t expected = 1;
  for (std::size_t n : shape) expected *= n;
  if (shape.empty() || expected != count)
    throw std::invalid_argument("encode_npy_array: data size does not match the shape");
  std::string dims;
  for (std::size_t n : shape) dims += std::to_string(n) + ", ";
  dims.resize(dims.size() - (shape.size() == 1 ? 1 : 2));  // (n,) for one axis, (a, b) otherwise
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + dims + "), }";
  // magic (6) + version (2) + header length (2) + header, padded with spaces and '\n' to 64 bytes.
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(static_cast<char>(header.size() & 0xff));
  out.push_back(static_cast<char>(header.size() >> 8));
  out += header;
  out.reserve(out.size() + count * 8);
  for (std::size_t i = 0; i < count; ++i) {  // little-endian whatever the host
    std::uint64_t bits = 0;
    std::memcpy(&bits, &data[i], sizeof bits);
    for (int b = 0; b < 8; ++b) out.push_back(static_cast<char>((bits >> (8 * b)) & 0xff));
  }
  return out;
}

std::string encode_npy_array(const std::vector<double>& data, const std::vector<std::size_t>& shape) {
  return encode_npy_array(data.data(), data.size(), shape);
}

}  // namespace rayint
