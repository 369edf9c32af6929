#pragma once
// A float64 array as a NumPy .npy file (format version 1.0, '<f8', C order), for the gradient
// arrays of `rayint render --grad-out` (render/mesh_gradient.hpp). Images use float_image.hpp.
#include <cstddef>
#include <string>
#include <vector>

namespace rayint {

// `data` holds the product of `shape` values in C order; throws std::invalid_argument otherwise.
std::string encode_npy_array(const std::vector<double>& data, const std::vector<std::size_t>& shape);

}  // namespace rayint
