#pragma once
// `rayint eval` of a mesh case whose file holds cells other than tetrahedra, in the cells' own
// interpolation ("mode": "own", mesh/cell_traversal.hpp): per ray the composite of its chords
// integrated in double (cells/cell_integral.hpp) and, unless skipped, the same chords integrated
// by the independent 50-digit cell reference (reference/cell_reference.hpp) and composited in long
// double, with the absolute difference (the largest channel of emission and optical depth).
// A ray whose chord could not be located or integrated is failed: its value and error are not
// numbers (null in JSON) and it is counted. The reference checks the integration along the
// traversal's chords; the chords themselves are checked against every cell's own chord in the
// tests ([celltraversal]).
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/reference/cell_reference.hpp"

namespace rayint {

struct OwnRayEvaluation {
  bool converged = true;
  std::string failure;          // why not (empty when converged)
  Rgb intensity{}, emission{}, optical_depth{};
  double error_estimate = 0.0;  // the double path's own estimate (sum over chords)
  long chords = 0;
  bool referenced = false;      // the 50-digit reference ran and succeeded
  std::string reference_failure;
  Rgb reference_intensity{};
  double abs_error = 0.0;       // max over channels of |emission - ref| and |depth - ref|
};

struct OwnCaseEvaluation {
  std::string name, source, mesh_source;
  std::vector<std::pair<std::string, long>> cells;  // by type
  std::size_t faces = 0, boundary_faces = 0;
  // Zero-volume cells the reader dropped (mesh/cell_mesh.hpp drop_zero_volume_cells), by type.
  long dropped_zero_volume = 0;
  std::map<std::string, long> dropped_zero_volume_by_type;
  std::vector<OwnRayEvaluation> rays;
  long failed = 0;                 // rays not converged
  long reference_failed = 0;
  double max_abs_error = 0.0;      // over referenced rays
  double seconds_per_ray = 0.0;    // traversal + integration, mean (no reference)
  CellTraversalStats traversal;
};

// The 50-digit cell reference's input (reference/cell_reference.hpp) for the chord [t_near, t_far]
// of the ray origin + t direction through `cell`: its VTK type, nodes and values, as doubles.
// (The cell tests, tools/cell_accuracy and bench/bench_cells build theirs with it too.)
CellReferenceInput cell_reference_input(const LinearCell& cell, const Vec3& origin, const Vec3& direction,
                                        double t_near, double t_far);
// Likewise for a quadratic cell (VTK ids 24-26) with all its nodes.
CellReferenceInput cell_reference_input(const QuadraticCell& cell, const Vec3& origin, const Vec3& direction,
                                        double t_near, double t_far);

// `mesh_case.cells` must be set. threads: for the reference (0 = all cores).
OwnCaseEvaluation evaluate_own_cells(const MeshCase& mesh_case, bool with_reference, unsigned threads = 0);

// Cases in the own interpolation are evaluated alone: the methods take linear segments, so they
// cannot be mixed with segment cases nor given methods. Throws InputError naming the first own
// case's file and `methods_field` (the caller's spelling: "--methods" for the CLI, "methods" in
// Python); `split_option` is how the caller asks for VTK's split ("--cells split").
void require_own_cases_alone(const std::vector<MeshCase>& own, const std::string& first_segment_case_source,
                             bool methods_given, const std::string& methods_field, const std::string& split_option);

}  // namespace rayint
