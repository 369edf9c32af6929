#pragma once
// What the tests of VTK's cells in their own interpolation, the linear cells
// (tests/test_linear_cells.cpp) and the quadratic ones (tests/test_quadratic_isoparametric.cpp),
// share: random points of a reference cell, a chord's double integral checked against the
// 50-digit reference, and the sweep of chords that does it over random cells (their bounds are
// LinearCellTolerances and QuadraticCellTolerances in tolerances.hpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rayint/cells/cell_integral.hpp"
#include "rayint/cells/linear_cells.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "rayint/studies/own_cells_eval.hpp"
#include "cell_samples.hpp"

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

// The reference sweeps of both files: random cells (linear or quadratic) drawn from `rng`, rays
// through them, each interval of a chord integrated in double with breakpoint_tf, required to
// converge, and checked by check_against_reference within `rel`; `worst` and `chords` are the
// largest relative error and the number of intervals checked so far.
struct ReferenceChordSweep {
  ReferenceChordSweep(double rel_, unsigned seed) : rel(rel_), rng(seed) {}
  ReferenceChordSweep(const ReferenceChordSweep&) = delete;  // the integrator points at tf
  ReferenceChordSweep& operator=(const ReferenceChordSweep&) = delete;

  double uniform() { return u(rng); }  // in [0, 1)
  // A ray aimed at `target` from 8 units away, in a random direction.
  ViewRay ray_at(const Vec3& target) {
    const Vec3 dir = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    return ViewRay{target - 8.0 * dir, dir};
  }

  // Every interval of `ch`, the chord of `cell` along `ray`; `label` names the cell in a failure.
  // Returns the intervals' integrals, for the caller's own checks.
  template <class Cell>
  std::vector<CellPieceIntegral> check(const Cell& cell, const ViewRay& ray, const Chord& ch,
                                       const std::string& label) {
    std::vector<CellPieceIntegral> done;
    for (const ChordInterval& iv : ch.intervals) {
      const CellPieceIntegral d = integrator.integrate(cell, ray, iv.t_near, iv.t_far);
      INFO(label << ": " << d.failure);
      REQUIRE(d.converged);
      const CellReference ref =
          reference_cell_chord(tf, cell_reference_input(cell, ray.origin, ray.direction, iv.t_near, iv.t_far));
      worst = std::max(worst, check_against_reference(d, ref, rel));
      ++chords;
      done.push_back(d);
    }
    return done;
  }

  const TransferFunctions tf = breakpoint_tf();
  const LinearCellIntegrator integrator{tf};
  const double rel;
  std::mt19937 rng;
  std::uniform_real_distribution<double> u{0.0, 1.0};
  double worst = 0.0;
  int chords = 0;
};

}  // namespace rayint::test
