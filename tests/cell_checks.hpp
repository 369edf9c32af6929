#pragma once
// The check the tests of VTK's cells in their own interpolation, the linear cells
// (tests/test_linear_cells.cpp) and the quadratic ones (tests/test_quadratic_isoparametric.cpp),
// share: a chord's double integral against the 50-digit reference (their bounds are
// LinearCellTolerances and QuadraticCellTolerances in tolerances.hpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/reference/cell_reference.hpp"

namespace rayint::test {

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
