// Straight-edged quadratic tetrahedra: edge check, field, chord polynomial and the trace integral
// (see quadratic_tets.hpp).
#include "rayint/mesh/quadratic_tets.hpp"

#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "rayint/cells/cell_types.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/mesh/tet_traversal.hpp"

namespace rayint {

Tet10EdgeCheck check_tet10_edges(const TetMesh& mesh) {
  Tet10EdgeCheck out;
  for (std::size_t t = 0; t < mesh.edge_nodes.size() && t < mesh.tets.size(); ++t) {
    bool quadratic = false;
    for (std::size_t e = 0; e < 6; ++e) {
      const std::int32_t m = mesh.edge_nodes[t][e];
      if (m < 0) continue;
      quadratic = true;
      const Vec3& a = mesh.points[static_cast<std::size_t>(mesh.tets[t][static_cast<std::size_t>(kTet10Edges[e][0])])];
      const Vec3& b = mesh.points[static_cast<std::size_t>(mesh.tets[t][static_cast<std::size_t>(kTet10Edges[e][1])])];
      const double length = (b - a).norm();
      const double off = (mesh.points[static_cast<std::size_t>(m)] - 0.5 * (a + b)).norm();
      // A zero-length edge belongs to a degenerate tet (dropped by repair): any offset is curved.
      const double rel = length > 0.0 ? off / length : (off > 0.0 ? HUGE_VAL : 0.0);
      if (rel > out.worst_offset || !std::isfinite(rel)) {
        out.worst_offset = rel;
        out.worst_tet = t;
        out.worst_edge = static_cast<int>(e);
      }
    }
    out.quadratic_tets += quadratic;
  }
  return out;
}

void refuse_curved_tet10(const TetMesh& mesh, const std::string& source) {
  const Tet10EdgeCheck c = check_tet10_edges(mesh);
  if (c.straight()) return;
  const long long id = mesh.info.cell_ids.size() == mesh.tets.size() ? mesh.info.cell_ids[c.worst_tet]
                                                                     : static_cast<long long>(c.worst_tet);
  const auto& edge = kTet10Edges[static_cast<std::size_t>(c.worst_edge)];
  throw InputError(source + ": cells[" + std::to_string(id) + "]: quadratic tetra with a curved edge: its node " +
                   std::to_string(4 + c.worst_edge) + " (edge " + std::to_string(edge[0]) + "-" +
                   std::to_string(edge[1]) + ") is " + format_number(c.worst_offset) +
                   " of the edge length off the midpoint (straight within " + format_number(kStraightEdgeTolerance) +
                   " is required; curved quadratic tetrahedra are not integrated yet)");
}

void refuse_quadratic_tets(const TetMesh& mesh, const std::string& source, const std::string& what) {
  const long n = check_tet10_edges(mesh).quadratic_tets;
  if (n == 0) return;
  throw InputError(source + ": cells: " + std::to_string(n) + " quadratic tetrahedra: " + what +
                   " takes linear tetrahedra only; `rayint render` integrates them with their quadratic interpolation");
}

QuadraticTetField fit_quadratic_tet(const TetMesh& mesh, std::size_t tet) {
  QuadraticTetField f;
  const auto& t = mesh.tets[tet];
  const auto point = [&](std::int32_t i) -> const Vec3& { return mesh.points[static_cast<std::size_t>(i)]; };
  f.p0 = point(t[0]);
  Eigen::Matrix3d A;
  for (int k = 0; k < 3; ++k) A.col(k) = point(t[static_cast<std::size_t>(k) + 1]) - f.p0;
  // lambda_(1..3) = A^-1 (x - p0): the rows of A^-1 are the gradients.
  const Eigen::Matrix3d inv = A.inverse();
  for (int k = 0; k < 3; ++k) f.grad[static_cast<std::size_t>(k)] = inv.row(k).transpose();
  const auto scalar = [&](std::int32_t i) { return mesh.scalars[static_cast<std::size_t>(i)]; };
  for (std::size_t k = 0; k < 4; ++k) f.value[k] = scalar(t[k]);
  for (std::size_t e = 0; e < 6; ++e) {
    const std::int32_t m = mesh.edge_nodes.empty() ? -1 : mesh.edge_nodes[tet][e];
    f.value[4 + e] = m >= 0 ? scalar(m)
                            : 0.5 * (f.value[static_cast<std::size_t>(kTet10Edges[e][0])] +
                                     f.value[static_cast<std::size_t>(kTet10Edges[e][1])]);
  }
  return f;
}

namespace {
// lambda_k(x_in + t d) = alpha[k] + beta[k] t, k = 0..3.
void barycentric_line(const QuadraticTetField& f, const Vec3& x_in, const Vec3& d, std::array<double, 4>& alpha,
                      std::array<double, 4>& beta) {
  const Vec3 r = x_in - f.p0;
  alpha[0] = 1.0;
  beta[0] = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    alpha[k + 1] = f.grad[k].dot(r);
    beta[k + 1] = f.grad[k].dot(d);
    alpha[0] -= alpha[k + 1];
    beta[0] -= beta[k + 1];
  }
}
}  // namespace

std::array<double, 3> quadratic_tet_chord(const QuadraticTetField& f, const Vec3& x_in, const Vec3& d) {
  std::array<double, 4> a{}, b{};
  barycentric_line(f, x_in, d, a, b);
  std::array<double, 3> c{0.0, 0.0, 0.0};
  // Corners: lambda (2 lambda - 1) = (2a^2 - a) + (4ab - b) t + 2b^2 t^2.
  for (std::size_t i = 0; i < 4; ++i) {
    const double v = f.value[i];
    c[0] += v * a[i] * (2.0 * a[i] - 1.0);
    c[1] += v * b[i] * (4.0 * a[i] - 1.0);
    c[2] += v * 2.0 * b[i] * b[i];
  }
  // Edges: 4 lambda_p lambda_q = 4 (a_p a_q + (a_p b_q + a_q b_p) t + b_p b_q t^2).
  for (std::size_t e = 0; e < 6; ++e) {
    const auto p = static_cast<std::size_t>(kTet10Edges[e][0]), q = static_cast<std::size_t>(kTet10Edges[e][1]);
    const double v = 4.0 * f.value[4 + e];
    c[0] += v * a[p] * a[q];
    c[1] += v * (a[p] * b[q] + a[q] * b[p]);
    c[2] += v * b[p] * b[q];
  }
  return c;
}

double quadratic_tet_value(const QuadraticTetField& f, const Vec3& x) {
  return quadratic_tet_chord(f, x, Vec3::Zero())[0];
}

PolyRay poly_ray_from_trace(const RayTrace& trace, const Rgb& background) {
  PolyRay r;
  r.background = background;
  r.segments.reserve(trace.crossings.size());
  for (auto it = trace.crossings.rbegin(); it != trace.crossings.rend(); ++it) {
    const double L = it->t_out - it->t_in;
    // f(t_in + tau) = s_in + w tau + q tau^2 with s_out = s_in + w L + q L^2; from the far end
    // (tau = L - s): f = s_out - (w + 2 q L) s + q s^2, and w + 2 q L = (s_out - s_in)/L + q L.
    const double g = L > 0.0 ? (it->s_out - it->s_in) / L + it->q * L : 0.0;
    r.segments.push_back(PolySegment{L, {it->s_out, -g, it->q}});
  }
  return r;
}

RayResult QuadraticTraceIntegrator::integrate(const RayTrace& trace, const Rgb& background, long* pieces) const {
  const TrilinearRayResult t = poly_.integrate(poly_ray_from_trace(trace, background));
  if (pieces) *pieces += t.pieces;
  return RayResult{t.intensity, t.transmittance};
}

}  // namespace rayint
