#pragma once
// A float64 array as a NumPy .npy file (format version 1.0, '<f8', C order), for the gradient
// arrays of `rayint render --grad-out` (render/mesh_gradient.hpp) and for images (float_image.hpp:
// encode_npy writes shape (H, W, 3) through it).
#include <cstddef>
#include <string>
#include <vector>

namespace rayint {

// `data` holds the product of `shape` values in C order; throws std::invalid_argument otherwise.
std::string encode_npy_array(const std::vector<double>& data, const std::vector<std::size_t>& shape);
std::string encode_npy_array(const double* data, std::size_t count, const std::vector<std::size_t>& shape);

}  // namespace rayint
