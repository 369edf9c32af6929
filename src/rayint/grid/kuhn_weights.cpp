#include "rayint/grid/kuhn_weights.hpp"

#include <algorithm>
#include <cmath>

namespace rayint {

KuhnWeights kuhn_weights(const VoxelGrid& grid, const Vec3& p) {
  const auto& dims = grid.dims();
  const Vec3 x = (p - grid.origin()).cwiseQuotient(grid.spacing());
  std::array<int, 3> c{};
  std::array<double, 3> u{};
  for (int i = 0; i < 3; ++i) {  // kuhn_value's cube and local coordinate, clamped to the grid
    const double xi = std::clamp(x[i], 0.0, static_cast<double>(dims[i] - 1));
    c[i] = std::min(static_cast<int>(std::floor(xi)), dims[i] - 2);
    u[i] = xi - c[i];
  }
  std::array<int, 3> axis{0, 1, 2};
  std::sort(axis.begin(), axis.end(), [&](int a, int b) { return u[a] > u[b]; });
  const auto index = [&](const std::array<int, 3>& v) {
    return static_cast<std::size_t>(v[0]) +
           static_cast<std::size_t>(dims[0]) *
               (static_cast<std::size_t>(v[1]) + static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(v[2]));
  };
  KuhnWeights w;
  std::array<int, 3> vtx = c;
  w.index[0] = index(vtx);
  w.weight[0] = 1.0 - u[axis[0]];
  for (int m = 0; m < 3; ++m) {
    ++vtx[axis[m]];
    w.index[static_cast<std::size_t>(m + 1)] = index(vtx);
    w.weight[static_cast<std::size_t>(m + 1)] = m < 2 ? u[axis[m]] - u[axis[m + 1]] : u[axis[2]];
  }
  return w;
}

}  // namespace rayint
