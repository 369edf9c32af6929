// `rayint eval` in the own mode (see own_cells_eval.hpp).
#include "rayint/studies/own_cells_eval.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rayint/core/error.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/reference/cell_reference.hpp"

namespace rayint {

namespace {

template <class Cell>
CellReferenceInput reference_input_of(const Cell& cell, int nodes, const Vec3& origin, const Vec3& direction,
                                      double t_near, double t_far) {
  CellReferenceInput in;
  in.vtk_id = static_cast<int>(cell.type);
  for (int i = 0; i < nodes; ++i) {
    const Vec3& x = cell.x[static_cast<std::size_t>(i)];
    in.nodes.push_back({x[0], x[1], x[2]});
    in.values.push_back(cell.value[static_cast<std::size_t>(i)]);
  }
  in.origin = {origin[0], origin[1], origin[2]};
  in.direction = {direction[0], direction[1], direction[2]};
  in.t_near = t_near;
  in.t_far = t_far;
  return in;
}

// The reference's input for cell c's chord [a, b]: a quadratic cell with all its nodes (ids 24-26),
// a linear one with its corners.
CellReferenceInput reference_input(const CellTraversal& mesh, std::size_t c, const CellTrace& trace, double a, double b) {
  if (const QuadraticCell* q = mesh.quadratic_cell(c)) return cell_reference_input(*q, trace.origin, trace.direction, a, b);
  return cell_reference_input(mesh.cell(c), trace.origin, trace.direction, a, b);
}

}  // namespace

CellReferenceInput cell_reference_input(const LinearCell& cell, const Vec3& origin, const Vec3& direction,
                                        double t_near, double t_far) {
  return reference_input_of(cell, linear_node_count(cell.type), origin, direction, t_near, t_far);
}

CellReferenceInput cell_reference_input(const QuadraticCell& cell, const Vec3& origin, const Vec3& direction,
                                        double t_near, double t_far) {
  return reference_input_of(cell, quadratic_node_count(cell.type), origin, direction, t_near, t_far);
}

OwnCaseEvaluation evaluate_own_cells(const MeshCase& mc, bool with_reference, unsigned threads) {
  if (!mc.cells) throw std::invalid_argument(mc.source + ": not a mesh case of cells in their own interpolation");
  OwnCaseEvaluation out;
  out.name = mc.name;
  out.source = mc.source;
  out.mesh_source = mc.mesh_source;
  out.dropped_zero_volume = mc.repairs.zero_volume;
  out.dropped_zero_volume_by_type = mc.repairs.zero_volume_by_type;
  const CellTraversal mesh(*mc.cells, mc.mesh_source);
  out.cells = cell_counts(mesh.mesh());
  out.faces = mesh.face_count();
  out.boundary_faces = mesh.boundary_face_count();
  const LinearCellIntegrator integrator(mc.transfer);
  const std::vector<MeshViewRay> rays = evaluation_rays(mc);
  out.rays.resize(rays.size());
  std::vector<CellTrace> traces(rays.size());
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    mesh.trace(rays[i].ray, traces[i], &out.traversal);
    const CellRayResult r = mesh.integrate(traces[i], integrator, rays[i].background);
    OwnRayEvaluation& e = out.rays[i];
    e.converged = r.converged;
    e.failure = r.failure;
    e.intensity = r.intensity;
    e.emission = r.emission;
    e.optical_depth = r.optical_depth;
    e.error_estimate = r.error_estimate;
    e.chords = r.chords;
    if (!r.converged) ++out.failed;
  }
  if (!rays.empty())
    out.seconds_per_ray = std::chrono::duration<double>(Clock::now() - start).count() / static_cast<double>(rays.size());
  if (!with_reference) return out;
  parallel_for(static_cast<long long>(rays.size()), threads, [&](long long k) {
    const auto i = static_cast<std::size_t>(k);
    OwnRayEvaluation& e = out.rays[i];
    const CellTrace& trace = traces[i];
    try {
      std::array<long double, kChannels> c{}, d{};
      for (const CellChordOnRay& ch : trace.chords) {
        const double a = std::max(ch.t_in, trace.t_eye);
        if (!(ch.t_out > a)) continue;
        const CellReference r =
            reference_cell_chord(mc.transfer, reference_input(mesh, static_cast<std::size_t>(ch.cell), trace, a, ch.t_out));
        for (std::size_t q = 0; q < kChannels; ++q) {
          c[q] += std::exp(-d[q]) * static_cast<long double>(r.emission[q]);
          d[q] += static_cast<long double>(r.optical_depth[q]);
        }
      }
      double err = 0.0;
      for (std::size_t q = 0; q < kChannels; ++q) {
        e.reference_intensity[q] = static_cast<double>(c[q] + std::exp(-d[q]) * static_cast<long double>(rays[i].background[q]));
        err = std::max({err, std::fabs(e.emission[q] - static_cast<double>(c[q])),
                        std::fabs(e.optical_depth[q] - static_cast<double>(d[q]))});
      }
      e.referenced = true;
      e.abs_error = err;
    } catch (const std::exception& ex) {
      e.reference_failure = ex.what();
    }
  });
  for (const OwnRayEvaluation& e : out.rays) {
    if (!e.referenced) ++out.reference_failed;
    else if (e.converged) out.max_abs_error = std::max(out.max_abs_error, e.abs_error);
  }
  return out;
}

void require_own_cases_alone(const std::vector<MeshCase>& own, const std::string& first_segment_case_source,
                             bool methods_given, const std::string& methods_field, const std::string& split_option) {
  if (own.empty()) return;
  if (!first_segment_case_source.empty())
    throw InputError(own.front().source + ": mesh_file: cells other than tetrahedra (own interpolation) cannot be "
                     "evaluated together with segment cases (" + first_segment_case_source + "); run them separately or use " +
                     split_option);
  if (methods_given)
    throw InputError(own.front().source + ": " + methods_field + ": the own interpolation of cells other than tetrahedra is one "
                     "method (cells/cell_integral.hpp); " + split_option + " evaluates the methods on VTK's split");
}

}  // namespace rayint
