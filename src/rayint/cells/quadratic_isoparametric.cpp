// VTK's quadratic cells in their own isoparametric interpolation: validity, inverse map, faces as
// quadratic patches, ray-patch hits and chords (see quadratic_isoparametric.hpp for the methods
// and thresholds).
#include "rayint/cells/quadratic_isoparametric.hpp"

#include "rayint/cells/isoparametric_sums.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rayint {
namespace {

using Q = QuadraticCellType;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// VTK's mid-edge nodes: node first + k lies on edge k (vtkQuadraticTetra.h, vtkQuadraticHexahedron.h,
// vtkQuadraticWedge.h).
constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
constexpr int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
constexpr int kWedgeEdges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
constexpr int kPyramidEdges[8][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};  // vtkQuadraticPyramid.h

int mid_node(QuadraticCellType type, int a, int b) {
  const int(*edges)[2] = nullptr;
  int n = 0, first = 0;
  switch (type) {
    case Q::tetra: edges = kTetEdges, n = 6, first = 4; break;
    case Q::hexahedron:
    case Q::triquadratic_hexahedron: edges = kHexEdges, n = 12, first = 8; break;
    case Q::wedge:
    case Q::biquadratic_wedge: edges = kWedgeEdges, n = 9, first = 6; break;
    case Q::pyramid: edges = kPyramidEdges, n = 8, first = 5; break;
  }
  for (int e = 0; e < n; ++e)
    if ((edges[e][0] == a && edges[e][1] == b) || (edges[e][0] == b && edges[e][1] == a)) return first + e;
  throw std::logic_error("quadratic cells: no such edge");
}

int corner_count(QuadraticCellType type) { return linear_node_count(quadratic_corner_type(type)); }

// The node at the centre of a face with the given corners (the mean of their reference points),
// or -1: the face-centre nodes of the triquadratic hexahedron and of the biquadratic-quadratic
// wedge's quadrilaterals. Found by position so that it follows VTK's face tables whatever their order.
int centre_node(QuadraticCellType type, const std::array<int, 4>& corner, int count) {
  const std::vector<Vec3>& ref = quadratic_reference_nodes(type);
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < count; ++k) mean += ref[static_cast<std::size_t>(corner[static_cast<std::size_t>(k)])];
  mean /= count;
  for (std::size_t i = 0; i < ref.size(); ++i)
    if ((ref[i] - mean).cwiseAbs().maxCoeff() < 1e-12) return static_cast<int>(i);
  return -1;
}

// Face shape functions and their (u, v) derivatives: corners, then mid-edge nodes, then the
// centre when there is one (header).
void patch_functions(int count, bool centre, double u, double v, double* N, double* dNu, double* dNv) {
  if (centre) {  // biquadratic 9-node quadrilateral: Lagrange in u times Lagrange in v
    double lu[3], du[3], lv[3], dv[3];
    lagrange_1d(u, lu, du);
    lagrange_1d(v, lv, dv);
    // Grid indices of A, B, C, D, AB, BC, CD, DA, centre.
    static const int iu[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, iv[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
    for (int k = 0; k < 9; ++k) {
      N[k] = lu[iu[k]] * lv[iv[k]];
      dNu[k] = du[iu[k]] * lv[iv[k]];
      dNv[k] = lu[iu[k]] * dv[iv[k]];
    }
    return;
  }
  if (count == 3) {
    p2_triangle(u, v, N, dNu, dNv);
    return;
  }
  // Serendipity quadrilateral on (xi, eta) = (2u - 1, 2v - 1).
  const double xi = 2.0 * u - 1.0, eta = 2.0 * v - 1.0;
  static const double cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1};
  for (int k = 0; k < 4; ++k) {
    const double a = xi * cx[k], b = eta * cy[k];
    N[k] = 0.25 * (1.0 + a) * (1.0 + b) * (a + b - 1.0);
    dNu[k] = 2.0 * 0.25 * cx[k] * (1.0 + b) * (2.0 * a + b);
    dNv[k] = 2.0 * 0.25 * cy[k] * (1.0 + a) * (a + 2.0 * b);
  }
  // AB (eta = -1), BC (xi = 1), CD (eta = 1), DA (xi = -1).
  const double side[4] = {-1, 1, 1, -1};
  for (int k = 0; k < 4; ++k) {
    if (k % 2 == 0) {  // xi_i = 0
      const double b = eta * side[k];
      N[4 + k] = 0.5 * (1.0 - xi * xi) * (1.0 + b);
      dNu[4 + k] = 2.0 * (-xi * (1.0 + b));
      dNv[4 + k] = 2.0 * 0.5 * (1.0 - xi * xi) * side[k];
    } else {  // eta_i = 0
      const double a = xi * side[k];
      N[4 + k] = 0.5 * (1.0 + a) * (1.0 - eta * eta);
      dNu[4 + k] = 2.0 * 0.5 * side[k] * (1.0 - eta * eta);
      dNv[4 + k] = 2.0 * (-eta * (1.0 + a));
    }
  }
}

using Vec2 = Eigen::Vector2d;

struct Projected {
  std::array<Vec2, kMaxPatchNodes> g{};
  int count = 0;
  bool centre = false;
  int nodes() const { return patch_node_count(count, centre); }
  Vec2 at(double u, double v) const {
    double N[kMaxPatchNodes], du[kMaxPatchNodes], dv[kMaxPatchNodes];
    patch_functions(count, centre, u, v, N, du, dv);
    Vec2 s = Vec2::Zero();
    for (int k = 0; k < nodes(); ++k) s += N[k] * g[static_cast<std::size_t>(k)];
    return s;
  }
};

// Whether one component of the Bernstein coefficients is of one sign beyond tol (no zero there).
bool excluded(const Vec2* b, int n, double tol) {
  for (int c = 0; c < 2; ++c) {
    bool all_pos = true, all_neg = true;
    for (int k = 0; k < n; ++k) {
      all_pos = all_pos && b[k][c] > tol;
      all_neg = all_neg && b[k][c] < -tol;
    }
    if (all_pos || all_neg) return true;
  }
  return false;
}

// Newton on G(u, v) = 0 from (u, v); false when it does not converge.
bool patch_newton(const Projected& P, double& u, double& v, double scale) {
  double N[kMaxPatchNodes], du[kMaxPatchNodes], dv[kMaxPatchNodes];
  for (int it = 0; it < 30; ++it) {
    patch_functions(P.count, P.centre, u, v, N, du, dv);
    Vec2 G = Vec2::Zero(), Gu = Vec2::Zero(), Gv = Vec2::Zero();
    for (int k = 0; k < P.nodes(); ++k) {
      const Vec2& g = P.g[static_cast<std::size_t>(k)];
      G += N[k] * g, Gu += du[k] * g, Gv += dv[k] * g;
    }
    if (G.cwiseAbs().maxCoeff() <= 8 * kEps * scale) return true;
    const double det = Gu[0] * Gv[1] - Gv[0] * Gu[1];
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double su = (G[0] * Gv[1] - Gv[0] * G[1]) / det, sv = (Gu[0] * G[1] - G[0] * Gu[1]) / det;
    u -= su, v -= sv;
    if (!std::isfinite(u) || !std::isfinite(v) || std::abs(u) > 4.0 || std::abs(v) > 4.0) return false;
    if (std::max(std::abs(su), std::abs(sv)) <= 4 * kEps) return true;
  }
  return false;
}

struct Search {
  const Projected* P;
  double tol, scale;
  std::vector<std::array<double, 2>> roots;
  void leaf(double u, double v) {
    if (!patch_newton(*P, u, v, scale)) return;
    const double lo = -kFaceSlack, hi = 1.0 + kFaceSlack;
    if (!(u >= lo && v >= lo && (P->count == 3 ? u + v <= hi : (u <= hi && v <= hi)))) return;
    for (const auto& r : roots)
      if (std::abs(r[0] - u) + std::abs(r[1] - v) < 1e-9) return;
    roots.push_back({u, v});
  }
  void quad(double u0, double u1, double v0, double v1, int depth) {
    const double us[3] = {u0, 0.5 * (u0 + u1), u1}, vs[3] = {v0, 0.5 * (v0 + v1), v1};
    Vec2 F[3][3], B[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F[i][j] = P->at(us[i], vs[j]);
    Vec2 H[3][3];  // Bernstein along u
    for (int j = 0; j < 3; ++j) {
      H[0][j] = F[0][j], H[2][j] = F[2][j];
      H[1][j] = 2.0 * F[1][j] - 0.5 * (F[0][j] + F[2][j]);
    }
    for (int i = 0; i < 3; ++i) {  // then along v
      B[3 * i] = H[i][0], B[3 * i + 2] = H[i][2];
      B[3 * i + 1] = 2.0 * H[i][1] - 0.5 * (H[i][0] + H[i][2]);
    }
    if (excluded(B, 9, tol)) return;
    if (depth == kPatchDepth) return leaf(us[1], vs[1]);
    quad(u0, us[1], v0, vs[1], depth + 1);
    quad(us[1], u1, v0, vs[1], depth + 1);
    quad(u0, us[1], vs[1], v1, depth + 1);
    quad(us[1], u1, vs[1], v1, depth + 1);
  }
  void tri(const Vec2& a, const Vec2& b, const Vec2& c, int depth) {
    const Vec2 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    const Vec2 Fa = P->at(a[0], a[1]), Fb = P->at(b[0], b[1]), Fc = P->at(c[0], c[1]);
    const Vec2 B[6] = {Fa, Fb, Fc, 2.0 * P->at(ab[0], ab[1]) - 0.5 * (Fa + Fb),
                       2.0 * P->at(bc[0], bc[1]) - 0.5 * (Fb + Fc), 2.0 * P->at(ca[0], ca[1]) - 0.5 * (Fc + Fa)};
    if (excluded(B, 6, tol)) return;
    if (depth == kPatchDepth) {
      const Vec2 m = (a + b + c) / 3.0;
      return leaf(m[0], m[1]);
    }
    tri(a, ab, ca, depth + 1);
    tri(ab, b, bc, depth + 1);
    tri(ca, bc, c, depth + 1);
    tri(bc, ca, ab, depth + 1);
  }
};

}  // namespace

const char* quadratic_cell_name(QuadraticCellType type) {
  switch (type) {
    case Q::tetra: return "quadratic tetra";
    case Q::hexahedron: return "quadratic hexahedron";
    case Q::wedge: return "quadratic wedge";
    case Q::triquadratic_hexahedron: return "triquadratic hexahedron";
    case Q::biquadratic_wedge: return "biquadratic-quadratic wedge";
    case Q::pyramid: return "quadratic pyramid";
  }
  return "?";
}

LinearCellType quadratic_corner_type(QuadraticCellType type) {
  switch (type) {
    case Q::tetra: return LinearCellType::tetra;
    case Q::hexahedron:
    case Q::triquadratic_hexahedron: return LinearCellType::hexahedron;
    case Q::wedge:
    case Q::biquadratic_wedge: return LinearCellType::wedge;
    case Q::pyramid: return LinearCellType::pyramid;
  }
  return LinearCellType::hexahedron;
}

int quadratic_face_count(QuadraticCellType type) { return linear_face_count(quadratic_corner_type(type)); }

QuadraticFaceNodes quadratic_face(QuadraticCellType type, int face) {
  const FaceNodes f = linear_face(quadratic_corner_type(type), face);
  QuadraticFaceNodes q;
  q.count = f.count;
  for (int k = 0; k < f.count; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    q.corner[kk] = f.node[kk];
    q.mid[kk] = mid_node(type, f.node[kk], f.node[static_cast<std::size_t>((k + 1) % f.count)]);
  }
  q.centre = centre_node(type, q.corner, q.count);
  return q;
}

Vec3 quadratic_reference_centre(QuadraticCellType type) { return linear_reference_centre(quadratic_corner_type(type)); }

Vec3 cell_position(const QuadraticCell& cell, const Vec3& p) { return isoparametric_position(cell, p); }
double cell_scalar(const QuadraticCell& cell, const Vec3& p) { return isoparametric_scalar(cell, p); }
Eigen::Matrix3d cell_jacobian(const QuadraticCell& cell, const Vec3& p) { return isoparametric_jacobian(cell, p); }

QuadraticCell make_quadratic_cell(QuadraticCellType type, const std::vector<Vec3>& nodes,
                                  const std::vector<double>& values) {
  const int n = quadratic_node_count(type);
  const std::string name = quadratic_cell_name(type);
  if (static_cast<int>(nodes.size()) != n || static_cast<int>(values.size()) != n)
    throw std::invalid_argument("a " + name + " needs " + std::to_string(n) + " nodes and values");
  QuadraticCell c;
  c.type = type;
  const double magnitude = copy_finite_nodes(c, nodes, values, n, name);
  const int corners = corner_count(type);
  c.extent = largest_distance(c.x.data(), corners);
  if (!(c.extent > 0.0)) throw std::invalid_argument(name + ": all corners coincide");

  // det J on the lattice i / (kJacobianSamples - 1) of the domain (corners, mid-edge nodes, faces
  // and interior points) and at the centre: one sign, never near 0. The pyramid's top face t = 1
  // is its apex collapsed: det J = (1 - t)^2 g(r, s, t) for every pyramid (as VTK's linear one,
  // whose g is det [B_r, B_s, apex - B] of the base's bilinear map B), so its test is on
  // g = det J / (1 - t)^2, and its lattice stops below the apex at the levels 7/8, 15/16 and
  // 63/64 instead of t = 1 (a curved pyramid can fold there: a mid-edge node of an apex edge
  // moved by 15 % of the edge folded random test cells between t = 0.75 and 1, found as two
  // parametric points of one world point by the round-trip test).
  const bool pyramid = type == Q::pyramid;
  const LinearCellType corner_type = quadratic_corner_type(type);
  std::vector<Vec3> samples{quadratic_reference_centre(type)};
  const int m = kJacobianSamples - 1;
  std::vector<double> levels;
  for (int k = 0; k <= m; ++k) levels.push_back(double(k) / m);
  if (pyramid) {
    levels.pop_back();
    for (double t : {7.0 / 8.0, 15.0 / 16.0, 63.0 / 64.0}) levels.push_back(t);
  }
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= m; ++j)
      for (double t : levels) {
        const Vec3 p(double(i) / m, double(j) / m, t);
        if (inside_reference(corner_type, p, 1e-12)) samples.push_back(p);
      }
  const double floor = kJacobianFloor * c.extent * c.extent * c.extent;
  int sign = 0;
  for (const Vec3& p : samples) {
    const double collapse = pyramid ? (1.0 - p[2]) * (1.0 - p[2]) : 1.0;
    const double det = cell_jacobian(c, p).determinant() / collapse;
    const int s = det > floor ? 1 : (det < -floor ? -1 : 0);
    if (s == 0 || (sign != 0 && s != sign))
      throw std::invalid_argument(name + ": the isoparametric map is not one-to-one (det J" +
                                  (pyramid ? " / (1 - t)^2" : "") + " = " + std::to_string(det) +
                                  " at parametric point (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                                  std::to_string(p[2]) + "), " +
                                  (s == 0 ? "near zero" : "of the other sign than elsewhere") +
                                  "): a mid-edge node folds the cell");
    sign = s;
  }
  c.orientation = sign;

  // Affine: every node at the affine image of its reference node (the corner map's axes). Never a
  // pyramid: its collapsed apex is no affine image of the unit cube (as linear_cells.hpp).
  if (type == Q::pyramid) return c;
  const std::vector<Vec3>& ref = quadratic_reference_nodes(type);
  int axis_node[3] = {-1, -1, -1};
  for (int i = 0; i < corners; ++i)
    for (int a = 0; a < 3; ++a)
      if (axis_node[a] < 0 && ref[static_cast<std::size_t>(i)] == Vec3::Unit(a)) axis_node[a] = i;
  if (axis_node[0] >= 0 && axis_node[1] >= 0 && axis_node[2] >= 0) {
    const AffineFit fit = fit_affine(c.x.data(), ref, n, axis_node);
    if (fit.residual <= kAffineTolerance * magnitude) {
      c.affine = true;
      c.affine_inverse = fit.A.inverse();
      c.affine_origin = c.x[0];
    }
  }
  return c;
}

InverseMap inverse_map(const QuadraticCell& cell, const Vec3& world, const Vec3& start) {
  return isoparametric_inverse_map(cell, world, start);
}

InverseMap inverse_map(const QuadraticCell& cell, const Vec3& world) {
  return inverse_map(cell, world, quadratic_reference_centre(cell.type));
}

// ---- Faces ---------------------------------------------------------------------------------

QuadraticFacePatch canonical_quadratic_face(const QuadraticCell& cell, int face, const std::int64_t* global_ids) {
  const QuadraticFaceNodes f = quadratic_face(cell.type, face);
  const int n = f.count;
  std::array<int, 4> perm{};
  if (global_ids != nullptr) {
    std::array<std::int64_t, 4> ids{};
    for (int k = 0; k < n; ++k) ids[static_cast<std::size_t>(k)] = global_ids[f.corner[static_cast<std::size_t>(k)]];
    perm = canonical_face_order(ids, n);
  } else {
    std::array<Vec3, 4> xs{};
    for (int k = 0; k < n; ++k) xs[static_cast<std::size_t>(k)] = cell.x[static_cast<std::size_t>(f.corner[static_cast<std::size_t>(k)])];
    perm = canonical_face_order(xs, n);
  }
  QuadraticFacePatch out;
  out.count = n;
  for (int k = 0; k < n; ++k) {
    const int a = perm[static_cast<std::size_t>(k)], b = perm[static_cast<std::size_t>((k + 1) % n)];
    // Corner edge (a, b) of the cyclic order: mid[a] when b follows a, else mid[b].
    const int mid = (b == (a + 1) % n) ? f.mid[static_cast<std::size_t>(a)] : f.mid[static_cast<std::size_t>(b)];
    out.local[static_cast<std::size_t>(k)] = f.corner[static_cast<std::size_t>(a)];
    out.local[static_cast<std::size_t>(n + k)] = mid;
  }
  out.centre = f.centre >= 0;
  if (out.centre) out.local[static_cast<std::size_t>(2 * n)] = f.centre;
  for (int k = 0; k < patch_node_count(n, out.centre); ++k)
    out.node[static_cast<std::size_t>(k)] = cell.x[static_cast<std::size_t>(out.local[static_cast<std::size_t>(k)])];
  return out;
}

Vec3 patch_point(const PatchNodes& node, int count, bool centre, double u, double v) {
  double N[kMaxPatchNodes], du[kMaxPatchNodes], dv[kMaxPatchNodes];
  patch_functions(count, centre, u, v, N, du, dv);
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < patch_node_count(count, centre); ++k) x += N[k] * node[static_cast<std::size_t>(k)];
  return x;
}

void patch_control_box(const PatchNodes& node, int count, bool centre, Vec3& lo, Vec3& hi) {
  std::vector<Vec3> control;
  if (count == 3) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = node[static_cast<std::size_t>(k)];
      const Vec3& b = node[static_cast<std::size_t>((k + 1) % 3)];
      control.push_back(a);
      control.push_back(2.0 * node[static_cast<std::size_t>(3 + k)] - 0.5 * (a + b));
    }
  } else {
    // The 3 x 3 values on the grid {0, 1/2, 1}^2, then Bernstein along u and v (as Search::quad).
    Vec3 F[3][3], H[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F[i][j] = patch_point(node, 4, centre, 0.5 * i, 0.5 * j);
    for (int j = 0; j < 3; ++j) {
      H[0][j] = F[0][j], H[2][j] = F[2][j];
      H[1][j] = 2.0 * F[1][j] - 0.5 * (F[0][j] + F[2][j]);
    }
    for (int i = 0; i < 3; ++i) {
      control.push_back(H[i][0]);
      control.push_back(2.0 * H[i][1] - 0.5 * (H[i][0] + H[i][2]));
      control.push_back(H[i][2]);
    }
  }
  lo = hi = control.front();
  for (const Vec3& c : control) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
}

std::vector<PatchHit> intersect_quadratic_face(const PatchNodes& node, int count, bool centre, const ViewRay& ray) {
  std::vector<PatchHit> out;
  const int n_nodes = patch_node_count(count, centre);
  // A flat patch (every mid-edge node at its edge's midpoint and the centre node, if any, at the
  // corners' mean, to kAffineTolerance): the patch is the plane triangle / bilinear patch of its
  // corners, in the same (u, v).
  double magnitude = 0.0, offset = 0.0;
  for (int k = 0; k < n_nodes; ++k) magnitude = std::max(magnitude, node[static_cast<std::size_t>(k)].cwiseAbs().maxCoeff());
  for (int k = 0; k < count; ++k) {
    const Vec3 mid = 0.5 * (node[static_cast<std::size_t>(k)] + node[static_cast<std::size_t>((k + 1) % count)]);
    offset = std::max(offset, (node[static_cast<std::size_t>(count + k)] - mid).cwiseAbs().maxCoeff());
  }
  if (centre) {
    const Vec3 mean = 0.25 * (node[0] + node[1] + node[2] + node[3]);
    offset = std::max(offset, (node[8] - mean).cwiseAbs().maxCoeff());
  }
  if (offset <= kAffineTolerance * magnitude) {
    std::array<Vec3, 4> corners{};
    for (int k = 0; k < count; ++k) corners[static_cast<std::size_t>(k)] = node[static_cast<std::size_t>(k)];
    const FaceHits hits = intersect_face(corners, count, ray);
    for (int h = 0; h < hits.count; ++h) {
      const FaceHit& f = hits.hit[static_cast<std::size_t>(h)];
      out.push_back({f.t, f.u, f.v});
    }
    return out;
  }
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const double dn2 = d.squaredNorm();
  if (!(dn2 > 0.0) || !std::isfinite(dn2)) return out;
  const Vec3 e1 = d.unitOrthogonal(), e2 = d.normalized().cross(e1);
  Projected P;
  P.count = count;
  P.centre = centre;
  double scale = 0.0;
  for (int k = 0; k < n_nodes; ++k) {
    const Vec3 r = node[static_cast<std::size_t>(k)] - o;
    P.g[static_cast<std::size_t>(k)] = Vec2(e1.dot(r), e2.dot(r));
    scale = std::max(scale, P.g[static_cast<std::size_t>(k)].cwiseAbs().maxCoeff());
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) return out;
  Search s{&P, kPatchExclusion * scale, scale, {}};
  if (count == 3) s.tri(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), 0);
  else s.quad(0.0, 1.0, 0.0, 1.0, 0);
  for (const auto& r : s.roots) {
    const Vec3 x = patch_point(node, count, centre, r[0], r[1]);
    out.push_back({(x - o).dot(d) / dn2, r[0], r[1]});
  }
  std::sort(out.begin(), out.end(), [](const PatchHit& a, const PatchHit& b) { return a.t < b.t; });
  return out;
}

Chord quadratic_chord(const QuadraticCell& cell, const ViewRay& ray, const std::int64_t* global_ids) {
  Chord out;
  struct Hit {
    double t;
    int face;
    Vec3 p;  // parametric point of the hit
  };
  std::vector<Hit> hits;
  const std::vector<Vec3>& ref = quadratic_reference_nodes(cell.type);
  for (int f = 0; f < quadratic_face_count(cell.type); ++f) {
    const QuadraticFacePatch patch = canonical_quadratic_face(cell, f, global_ids);
    PatchNodes ref_nodes{};
    for (int k = 0; k < patch_node_count(patch.count, patch.centre); ++k)
      ref_nodes[static_cast<std::size_t>(k)] = ref[static_cast<std::size_t>(patch.local[static_cast<std::size_t>(k)])];
    for (const PatchHit& h : intersect_quadratic_face(patch.node, patch.count, patch.centre, ray))
      hits.push_back({h.t, f, patch_point(ref_nodes, patch.count, patch.centre, h.u, h.v)});
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t || (a.t == b.t && a.face < b.face); });
  for (const Hit& h : hits) out.hits.push_back({h.t, h.face});
  const LinearCellType corner_type = quadratic_corner_type(cell.type);
  for (std::size_t k = 0; k + 1 < hits.size(); ++k) {
    const double t0 = hits[k].t, t1 = hits[k + 1].t;
    if (!(t1 > t0)) continue;
    const double tm = 0.5 * (t0 + t1);
    const Vec3 x = ray.origin + tm * ray.direction;
    InverseMap m = inverse_map(cell, x, hits[k].p);
    if (!m.converged) m = inverse_map(cell, x);
    if (!m.converged) {
      out.failed = true;
      continue;
    }
    if (!inside_reference(corner_type, m.p, 1e-9)) continue;
    if (!out.intervals.empty() && out.intervals.back().t_far == t0)
      out.intervals.back().t_far = t1;
    else
      out.intervals.push_back({t0, t1});
  }
  return out;
}

}  // namespace rayint
