#pragma once
// What the tests of VTK's cells in their own interpolation, the linear cells
// (tests/test_linear_cells.cpp) and the quadratic ones (tests/test_quadratic_isoparametric.cpp),
// share: random points of a reference cell, and a chord's double integral checked against the
// 50-digit reference (their bounds are LinearCellTolerances and QuadraticCellTolerances in
// tolerances.hpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/reference/cell_reference.hpp"

namespace rayint::test {

// A uniformly random point of the reference cell of `type` (a quadratic cell: its corners' type).
inline Vec3 random_inside(LinearCellType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (inside_reference(type, p)) return p;
  }
}

// One chord interval's integral `d` in double against the 50-digit reference `ref`, per channel:
// emission and optical depth within `rel` of the reference (relative), and their errors' sum
// within d's own error estimate. Returns the largest relative error.
inline double check_against_reference(const CellPieceIntegral& d, const CellReference& ref, double rel) {
  double worst = 0.0;
  for (std::size_t c = 0; c < kChannels; ++c) {
    const double e = std::abs(d.emission[c] - ref.emission[c]), o = std::abs(d.optical_depth[c] - ref.optical_depth[c]);
    worst = std::max({worst, e / ref.emission[c], o / ref.optical_depth[c]});
    INFO("channel " << c << " path " << cell_path_name(d.path) << " pieces " << d.pieces << " degree "
                    << d.max_degree << " estimate " << d.error_estimate << " errors " << e / ref.emission[c] << " "
                    << o / ref.optical_depth[c]);
    CHECK(e <= rel * ref.emission[c]);
    CHECK(o <= rel * ref.optical_depth[c]);
    CHECK(e + o <= d.error_estimate);
  }
  return worst;
}

}  // namespace rayint::test
