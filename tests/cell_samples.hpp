#pragma once
// Linear-cell sample data shared by the cell tests (tests/test_linear_cells.cpp), the accuracy
// tool (tools/cell_accuracy.cpp) and the cell benchmark (bench/bench_cells.cpp): one copy of the
// transfer functions they measure with, and of the 50-digit reference's input for a cell's
// chord. Header-only test support: it adds nothing to the library's layers (tools and bench put
// tests/ on their include path for it).
#include "rayint/cells/linear_cells.hpp"
#include "rayint/reference/cell_reference.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace rayint::test {

// Density and colour with breakpoints inside a unit cell's value range [0, 1] (each channel its
// own): every chord through a cell with random node values crosses several of them.
inline TransferFunctions breakpoint_tf() {
  TransferFunctions tf;
  tf.density[0] = {{0.1, 0.3, 0.45, 0.7, 0.9}, {0.5, 4.0, 1.0, 6.0, 2.0}};
  tf.density[1] = {{0.2, 0.5, 0.8}, {0.0, 3.0, 0.5}};
  tf.density[2] = {{0.0, 0.35, 0.6, 1.0}, {1.0, 0.2, 5.0, 1.5}};
  tf.color[0] = {{0.0, 0.5, 1.0}, {1.0, 0.1, 0.8}};
  tf.color[1] = {{0.25, 0.55, 0.75}, {0.2, 1.0, 0.0}};
  tf.color[2] = {{0.4, 0.65}, {0.9, 0.3}};
  return tf;
}

// The reference's input (reference/cell_reference.hpp) for the chord [t_near, t_far] of `ray`
// through `cell`: studies/own_cells_eval.hpp's, which `rayint eval` uses.
inline CellReferenceInput reference_input(const LinearCell& cell, const ViewRay& ray, double t_near, double t_far) {
  return cell_reference_input(cell, ray.origin, ray.direction, t_near, t_far);
}

}  // namespace rayint::test
