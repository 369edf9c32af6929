// The linear VTK cells: shape functions, faces, inverse map, ray-face hits and chords (see
// linear_cells.hpp for the definitions, regions and thresholds).
#include "rayint/cells/linear_cells.hpp"

#include "rayint/cells/isoparametric_sums.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rayint {
namespace {

using T = LinearCellType;

// The voxel in hexahedron order: hexahedron node k is voxel node kVoxelToHex[k].
constexpr int kVoxelToHex[8] = {0, 1, 3, 2, 4, 5, 7, 6};

// VTK's face tables (Faces[] of each vtk<Cell>.cxx); voxel faces in cyclic order.
constexpr int kTetraFaces[4][4] = {{0, 1, 3, -1}, {1, 2, 3, -1}, {2, 0, 3, -1}, {0, 2, 1, -1}};
constexpr int kHexFaces[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                 {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
// VTK voxel faces {2,0,6,4} {1,3,5,7} {0,1,4,5} {3,2,7,6} {1,0,3,2} {4,5,6,7} are pixels
// (x fastest); as polygons: pixel (a, b, c, d) -> (a, b, d, c).
constexpr int kVoxelFaces[6][4] = {{2, 0, 4, 6}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {3, 2, 6, 7}, {1, 0, 2, 3}, {4, 5, 7, 6}};
constexpr int kWedgeFaces[5][4] = {{0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
constexpr int kPyramidFaces[5][4] = {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};

constexpr double kEps = std::numeric_limits<double>::epsilon();

void hex_functions(double r, double s, double t, double* N) {
  const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
  N[0] = rm * sm * tm;
  N[1] = r * sm * tm;
  N[2] = r * s * tm;
  N[3] = rm * s * tm;
  N[4] = rm * sm * t;
  N[5] = r * sm * t;
  N[6] = r * s * t;
  N[7] = rm * s * t;
}

void hex_derivatives(double r, double s, double t, double* dN) {
  const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
  // d/dr
  dN[0] = -sm * tm, dN[1] = sm * tm, dN[2] = s * tm, dN[3] = -s * tm;
  dN[4] = -sm * t, dN[5] = sm * t, dN[6] = s * t, dN[7] = -s * t;
  // d/ds
  dN[8] = -rm * tm, dN[9] = -r * tm, dN[10] = r * tm, dN[11] = rm * tm;
  dN[12] = -rm * t, dN[13] = -r * t, dN[14] = r * t, dN[15] = rm * t;
  // d/dt
  dN[16] = -rm * sm, dN[17] = -r * sm, dN[18] = -r * s, dN[19] = -rm * s;
  dN[20] = rm * sm, dN[21] = r * sm, dN[22] = r * s, dN[23] = rm * s;
}

}  // namespace

bool linear_cell_type_from_vtk(int vtk_id, LinearCellType& type) {
  if (vtk_id < 10 || vtk_id > 14) return false;
  type = static_cast<LinearCellType>(vtk_id);
  return true;
}

const char* linear_cell_name(LinearCellType type) {
  switch (type) {
    case T::tetra: return "tetra";
    case T::voxel: return "voxel";
    case T::hexahedron: return "hexahedron";
    case T::wedge: return "wedge";
    case T::pyramid: return "pyramid";
  }
  return "?";
}

int linear_node_count(LinearCellType type) {
  switch (type) {
    case T::tetra: return 4;
    case T::voxel:
    case T::hexahedron: return 8;
    case T::wedge: return 6;
    case T::pyramid: return 5;
  }
  return 0;
}

int linear_face_count(LinearCellType type) {
  switch (type) {
    case T::tetra: return 4;
    case T::voxel:
    case T::hexahedron: return 6;
    case T::wedge:
    case T::pyramid: return 5;
  }
  return 0;
}

void linear_shape_functions(LinearCellType type, const Vec3& p, double* N) {
  const double r = p[0], s = p[1], t = p[2];
  switch (type) {
    case T::tetra:
      N[0] = 1.0 - r - s - t, N[1] = r, N[2] = s, N[3] = t;
      return;
    case T::hexahedron: hex_functions(r, s, t, N); return;
    case T::voxel: {
      double h[8];
      hex_functions(r, s, t, h);
      for (int k = 0; k < 8; ++k) N[kVoxelToHex[k]] = h[k];
      return;
    }
    case T::wedge: {
      const double w = 1.0 - r - s, tm = 1.0 - t;
      N[0] = w * tm, N[1] = r * tm, N[2] = s * tm, N[3] = w * t, N[4] = r * t, N[5] = s * t;
      return;
    }
    case T::pyramid: {
      const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
      N[0] = rm * sm * tm, N[1] = r * sm * tm, N[2] = r * s * tm, N[3] = rm * s * tm, N[4] = t;
      return;
    }
  }
}

void linear_shape_derivatives(LinearCellType type, const Vec3& p, double* dN) {
  const double r = p[0], s = p[1], t = p[2];
  switch (type) {
    case T::tetra: {
      const double d[12] = {-1, 1, 0, 0, -1, 0, 1, 0, -1, 0, 0, 1};
      std::copy(d, d + 12, dN);
      return;
    }
    case T::hexahedron: hex_derivatives(r, s, t, dN); return;
    case T::voxel: {
      double h[24];
      hex_derivatives(r, s, t, h);
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 8; ++k) dN[8 * j + kVoxelToHex[k]] = h[8 * j + k];
      return;
    }
    case T::wedge: {
      const double w = 1.0 - r - s, tm = 1.0 - t;
      const double d[18] = {-tm, tm, 0, -t, t, 0,     // d/dr
                            -tm, 0, tm, -t, 0, t,     // d/ds
                            -w, -r, -s, w, r, s};     // d/dt
      std::copy(d, d + 18, dN);
      return;
    }
    case T::pyramid: {
      const double rm = 1.0 - r, sm = 1.0 - s, tm = 1.0 - t;
      const double d[15] = {-sm * tm, sm * tm, s * tm, -s * tm, 0,             // d/dr
                            -rm * tm, -r * tm, r * tm, rm * tm, 0,             // d/ds
                            -rm * sm, -r * sm, -r * s, -rm * s, 1};            // d/dt
      std::copy(d, d + 15, dN);
      return;
    }
  }
}

const std::vector<Vec3>& linear_reference_nodes(LinearCellType type) {
  static const std::vector<Vec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const std::vector<Vec3> hex = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  static const std::vector<Vec3> voxel = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  static const std::vector<Vec3> wedge = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  static const std::vector<Vec3> pyramid = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
  switch (type) {
    case T::tetra: return tetra;
    case T::voxel: return voxel;
    case T::hexahedron: return hex;
    case T::wedge: return wedge;
    case T::pyramid: return pyramid;
  }
  return hex;
}

Vec3 linear_reference_centre(LinearCellType type) {
  switch (type) {
    case T::tetra: return Vec3::Constant(0.25);
    case T::wedge: return Vec3(1.0 / 3.0, 1.0 / 3.0, 0.5);
    case T::pyramid: return Vec3(0.5, 0.5, 0.25);  // the pyramid's centroid (height 1/4)
    default: return Vec3::Constant(0.5);
  }
}

bool inside_reference(LinearCellType type, const Vec3& p, double slack) {
  const double lo = -slack, hi = 1.0 + slack;
  switch (type) {
    case T::tetra: return p[0] >= lo && p[1] >= lo && p[2] >= lo && p.sum() <= hi;
    case T::wedge: return p[0] >= lo && p[1] >= lo && p[0] + p[1] <= hi && p[2] >= lo && p[2] <= hi;
    default: return (p.array() >= lo).all() && (p.array() <= hi).all();
  }
}

FaceNodes linear_face(LinearCellType type, int face) {
  const int(*table)[4] = nullptr;
  switch (type) {
    case T::tetra: table = kTetraFaces; break;
    case T::voxel: table = kVoxelFaces; break;
    case T::hexahedron: table = kHexFaces; break;
    case T::wedge: table = kWedgeFaces; break;
    case T::pyramid: table = kPyramidFaces; break;
  }
  if (face < 0 || face >= linear_face_count(type)) throw std::out_of_range("linear_face: no such face");
  FaceNodes f;
  for (int k = 0; k < 4; ++k) f.node[static_cast<std::size_t>(k)] = table[face][k];
  f.count = table[face][3] < 0 ? 3 : 4;
  return f;
}

namespace {

struct Monomials {
  double r, s, t, rs, rt, st, rst;
  explicit Monomials(const Vec3& p)
      : r(p[0]), s(p[1]), t(p[2]), rs(p[0] * p[1]), rt(p[0] * p[2]), st(p[1] * p[2]), rst(p[0] * p[1] * p[2]) {}
};

Vec3 position(const MultilinearForm& m, const Monomials& q) {
  return m.x[0] + q.r * m.x[1] + q.s * m.x[2] + q.t * m.x[3] + q.rs * m.x[4] + q.rt * m.x[5] + q.st * m.x[6] +
         q.rst * m.x[7];
}

Eigen::Matrix3d jacobian(const MultilinearForm& m, const Monomials& q) {
  Eigen::Matrix3d J;
  J.col(0) = m.x[1] + q.s * m.x[4] + q.t * m.x[5] + q.st * m.x[7];
  J.col(1) = m.x[2] + q.r * m.x[4] + q.t * m.x[6] + q.rt * m.x[7];
  J.col(2) = m.x[3] + q.r * m.x[5] + q.s * m.x[6] + q.rs * m.x[7];
  return J;
}


// The coefficients of a per-node quantity (positions, scalars) in the monomials 1, r, s, t, rs,
// rt, st, rst: its values at the corners q of the unit cube (bit 0: r, bit 1: s, bit 2: t) from
// the nodal form, then Moebius inversion (the coefficient of the monomial with exponent bits m
// is the alternating sum over the corners q contained in m). A hexahedron's or voxel's corners
// are its nodes (the shape functions are exactly 0 and 1 there, so reading the node is the
// same value bit for bit); a wedge's, pyramid's or tetra's corners outside the domain come
// from the shape functions, which are polynomials.
template <class V>
std::array<V, 8> monomial_coefficients(LinearCellType type, const V* node, const V& zero) {
  constexpr int kHexCorner[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // node at corner q
  const int n = linear_node_count(type);
  std::array<V, 8> corner;
  double N[kMaxLinearNodes];
  for (int q = 0; q < 8; ++q) {
    const auto Q = static_cast<std::size_t>(q);
    if (type == LinearCellType::hexahedron) {
      corner[Q] = node[kHexCorner[q]];
    } else if (type == LinearCellType::voxel) {
      corner[Q] = node[q];
    } else {
      linear_shape_functions(type, Vec3((q & 1) ? 1.0 : 0.0, (q & 2) ? 1.0 : 0.0, (q & 4) ? 1.0 : 0.0), N);
      V v = zero;
      for (int i = 0; i < n; ++i) v += N[i] * node[i];
      corner[Q] = v;
    }
  }
  constexpr int kBits[8] = {0, 1, 2, 4, 3, 5, 6, 7};  // slots 1, r, s, t, rs, rt, st, rst
  std::array<V, 8> out;
  for (int slot = 0; slot < 8; ++slot) {
    const int bits = kBits[slot];
    V v = zero;
    for (int q = 0; q < 8; ++q) {
      if ((q & ~bits) != 0) continue;
      const int parity = __builtin_popcount(static_cast<unsigned>(bits ^ q)) % 2;
      v += (parity == 0 ? 1.0 : -1.0) * corner[static_cast<std::size_t>(q)];
    }
    out[static_cast<std::size_t>(slot)] = v;
  }
  return out;
}

// The multilinear form (MultilinearForm; chord_scalar.hpp describes it): x's monomial
// coefficients, and f's of f_i - midrange (f[1..7] are f's, with rounding scaled by the spread).
MultilinearForm multilinear_form(const LinearCell& cell) {
  MultilinearForm m;
  const int n = linear_node_count(cell.type);
  for (int i = 0; i < n; ++i) m.magnitude = std::max(m.magnitude, cell.x[static_cast<std::size_t>(i)].cwiseAbs().maxCoeff());
  m.x = monomial_coefficients<Vec3>(cell.type, cell.x.data(), Vec3::Zero());
  double f_lo = cell.value[0], f_hi = cell.value[0];
  for (int i = 1; i < n; ++i)
    f_lo = std::min(f_lo, cell.value[static_cast<std::size_t>(i)]), f_hi = std::max(f_hi, cell.value[static_cast<std::size_t>(i)]);
  const double f_ref = 0.5 * (f_lo + f_hi);
  std::array<double, kMaxLinearNodes> relative{};
  for (int i = 0; i < n; ++i) {
    relative[static_cast<std::size_t>(i)] = cell.value[static_cast<std::size_t>(i)] - f_ref;
    m.f_spread += std::abs(relative[static_cast<std::size_t>(i)]);
  }
  m.f = monomial_coefficients<double>(cell.type, relative.data(), 0.0);
  return m;
}

}  // namespace

Eigen::Matrix3d multilinear_jacobian(const MultilinearForm& m, const Vec3& p) { return jacobian(m, Monomials(p)); }

// inverse_map's iteration (newton_inverse_map) on the multilinear form: the same tolerances,
// budget and clamp. With `step_first` the residual test is skipped before the first step: a
// point that passes it by a hair (a Taylor prediction) still takes one step, and near a singular
// Jacobian (a pyramid's apex) the residual bound alone leaves the point off by |J^-1| 8 eps |x|.
bool multilinear_newton(const MultilinearForm& m, const Vec3& target, Vec3& p, bool step_first, int& steps) {
  const double residual_tolerance = 8 * std::numeric_limits<double>::epsilon() * std::max(m.magnitude, target.cwiseAbs().maxCoeff());
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    const Monomials q(p);
    const Vec3 residual = target - position(m, q);
    if (!(step_first && it == 0) && residual.cwiseAbs().maxCoeff() <= residual_tolerance) return true;
    Vec3 step = jacobian(m, q).inverse() * residual;
    ++steps;
    if (!step.allFinite()) return false;
    const double size = step.cwiseAbs().maxCoeff();
    if (size > kNewtonMaxStep) step *= kNewtonMaxStep / size;
    p += step;
    if (size <= kNewtonStepTolerance) return true;
  }
  return false;
}

LinearCell make_linear_cell(LinearCellType type, const std::vector<Vec3>& nodes,
                            const std::vector<double>& values) {
  const int n = linear_node_count(type);
  if (n == 0) throw std::invalid_argument("linear cell: unknown type");
  if (static_cast<int>(nodes.size()) != n || static_cast<int>(values.size()) != n)
    throw std::invalid_argument(std::string("linear cell: a ") + linear_cell_name(type) + " needs " +
                                std::to_string(n) + " nodes and values");
  LinearCell c;
  c.type = type;
  const double magnitude = copy_finite_nodes(c, nodes, values, n, "linear cell");
  c.extent = largest_distance(c.x.data(), n);
  if (!(c.extent > 0.0)) throw std::invalid_argument("linear cell: all nodes coincide");

  // Affine test: the nodes at p = 0 and at the three unit points define the candidate map.
  if (type != T::pyramid) {
    const std::vector<Vec3>& ref = linear_reference_nodes(type);
    int axis_node[3] = {-1, -1, -1};
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a)
        if (ref[static_cast<std::size_t>(i)] == Vec3::Unit(a)) axis_node[a] = i;
    const AffineFit fit = fit_affine(c.x.data(), ref, n, axis_node);
    const Eigen::Matrix3d& A = fit.A;
    const double scale = A.col(0).norm() * A.col(1).norm() * A.col(2).norm();
    if (fit.residual <= kAffineTolerance * magnitude && std::abs(A.determinant()) > 1e-12 * scale) {
      c.affine = true;
      c.affine_inverse = A.inverse();
      c.affine_origin = c.x[0];
    }
  }
  c.multilinear = multilinear_form(c);
  return c;
}

Vec3 cell_position(const LinearCell& cell, const Vec3& p) { return isoparametric_position(cell, p); }
double cell_scalar(const LinearCell& cell, const Vec3& p) { return isoparametric_scalar(cell, p); }
Eigen::Matrix3d cell_jacobian(const LinearCell& cell, const Vec3& p) { return isoparametric_jacobian(cell, p); }

Vec3 cell_scalar_gradient(const LinearCell& cell, const Vec3& p) {
  const int n = linear_node_count(cell.type);
  double dN[3 * kMaxLinearNodes];
  linear_shape_derivatives(cell.type, p, dN);
  Vec3 g = Vec3::Zero();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < n; ++i) g[j] += dN[j * n + i] * cell.value[static_cast<std::size_t>(i)];
  return g;
}

InverseMap inverse_map(const LinearCell& cell, const Vec3& world, const Vec3& start) {
  return isoparametric_inverse_map(cell, world, start);
}

InverseMap inverse_map(const LinearCell& cell, const Vec3& world) {
  return inverse_map(cell, world, linear_reference_centre(cell.type));
}

// ---- Faces ---------------------------------------------------------------------------------

namespace {

template <class Less>
std::array<int, 4> canonical_cyclic(int count, Less less) {
  int k = 0;
  for (int i = 1; i < count; ++i)
    if (less(i, k)) k = i;
  const int next = (k + 1) % count, prev = (k + count - 1) % count;
  const int dir = less(next, prev) ? 1 : count - 1;
  std::array<int, 4> perm{0, 1, 2, 3};
  for (int i = 0; i < count; ++i) perm[static_cast<std::size_t>(i)] = (k + i * dir) % count;
  return perm;
}

// An orthonormal pair perpendicular to the unit vector n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited").
void perpendicular_pair(const Vec3& n, Vec3& e1, Vec3& e2) {
  const double sign = std::copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]);
  const double b = n[0] * n[1] * a;
  e1 = Vec3(1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]);
  e2 = Vec3(b, sign + n[1] * n[1] * a, -n[1]);
}

}  // namespace

std::array<int, 4> canonical_face_order(const std::array<std::int64_t, 4>& global_ids, int count) {
  return canonical_cyclic(count, [&](int i, int j) {
    return global_ids[static_cast<std::size_t>(i)] < global_ids[static_cast<std::size_t>(j)];
  });
}

std::array<int, 4> canonical_face_order(const std::array<Vec3, 4>& coordinates, int count) {
  return canonical_cyclic(count, [&](int i, int j) {
    const Vec3& a = coordinates[static_cast<std::size_t>(i)];
    const Vec3& b = coordinates[static_cast<std::size_t>(j)];
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
}

RayFrame::RayFrame(const ViewRay& ray) : dn(ray.direction.norm()) {
  dir = ray.direction / dn;
  perpendicular_pair(dir, e0, e1);
}

FaceHits intersect_face(const std::array<Vec3, 4>& nodes, int count, const ViewRay& ray) {
  return intersect_face(nodes, count, ray, RayFrame(ray));
}

FaceHits intersect_face(const std::array<Vec3, 4>& nodes, int count, const ViewRay& ray, const RayFrame& frame) {
  FaceHits out;
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const double lo = -kFaceSlack, hi = 1.0 + kFaceSlack;
  if (count == 3) {  // Moller-Trumbore
    const Vec3 e1 = nodes[1] - nodes[0], e2 = nodes[2] - nodes[0];
    const Vec3 pvec = d.cross(e2);
    const double det = e1.dot(pvec);
    if (det == 0.0 || !std::isfinite(det)) return out;
    const Vec3 tvec = o - nodes[0];
    const double u = tvec.dot(pvec) / det;
    const Vec3 qvec = tvec.cross(e1);
    const double v = d.dot(qvec) / det;
    if (!(u >= lo && v >= lo && u + v <= hi)) return out;
    out.hit[0] = {e2.dot(qvec) / det, u, v, e1.cross(e2).dot(d)};
    out.count = 1;
    return out;
  }
  // Bilinear patch A B C D: P = A + u (B - A) + v (D - A) + u v (A - B + C - D).
  const Vec3 &A = nodes[0], &B = nodes[1], &C = nodes[2], &D = nodes[3];
  const Vec3 eu = B - A, ev = D - A, euv = (A - B) + (C - D);
  const double dn = frame.dn;
  const Vec3 e[2] = {frame.e0, frame.e1};
  double a[2], b[2], c[2], w[2];
  for (int k = 0; k < 2; ++k) {
    a[k] = e[k].dot(A - o), b[k] = e[k].dot(eu), c[k] = e[k].dot(ev), w[k] = e[k].dot(euv);
    // The corners' signed distances from plane k: A, B, D, C.
    const double pa = a[k], pb = a[k] + b[k], pd = a[k] + c[k], pc = pb + c[k] + w[k];
    const double margin = 2 * kFaceSlack * (std::abs(b[k]) + std::abs(c[k]) + std::abs(w[k])) +
                          16 * std::numeric_limits<double>::epsilon() *
                              (std::abs(a[k]) + std::abs(b[k]) + std::abs(c[k]) + std::abs(w[k]));
    if (std::min({pa, pb, pd, pc}) > margin || std::max({pa, pb, pd, pc}) < -margin) return out;
  }
  // (a0 + b0 u)(c1 + w1 u) - (a1 + b1 u)(c0 + w0 u) = 0
  const double qa = b[0] * w[1] - b[1] * w[0];
  const double qb = (a[0] * w[1] - a[1] * w[0]) + (b[0] * c[1] - b[1] * c[0]);
  const double qc = a[0] * c[1] - a[1] * c[0];
  double roots[2];
  int n_roots = 0;
  if (qa == 0.0) {
    if (qb != 0.0) roots[n_roots++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      roots[n_roots++] = q / qa;
      if (q != 0.0) roots[n_roots++] = qc / q;
    }
  }
  for (int i = 0; i < n_roots; ++i) {
    const double u = roots[i];
    if (!(u >= lo && u <= hi)) continue;
    const double den0 = c[0] + w[0] * u, den1 = c[1] + w[1] * u;
    double v;
    if (std::abs(den0) >= std::abs(den1)) {
      if (den0 == 0.0) continue;
      v = -(a[0] + b[0] * u) / den0;
    } else {
      v = -(a[1] + b[1] * u) / den1;
    }
    if (!(v >= lo && v <= hi)) continue;
    const Vec3 P = A + u * eu + v * ev + (u * v) * euv;
    const double t = (P - o).dot(d) / (dn * dn);
    const Vec3 normal = (eu + v * euv).cross(ev + u * euv);
    if (out.count == 1 && out.hit[0].t == t) continue;  // a double root
    out.hit[static_cast<std::size_t>(out.count++)] = {t, u, v, normal.dot(d)};
  }
  if (out.count == 2 && out.hit[1].t < out.hit[0].t) std::swap(out.hit[0], out.hit[1]);
  return out;
}

int classify_chord_intervals(const LinearCell& cell, const ViewRay& ray, const double* ts, int n_ts, ChordInterval* out,
                             bool& failed) {
  int n_out = 0;
  Vec3 start = linear_reference_centre(cell.type);
  // Curved cells: inverse_map's Newton on the multilinear form (the same iteration, tolerances
  // and budget; cheaper per step: ~6 % -> ~3 % of `rayint bench` twisted12, 2026-12-05);
  // affine ones: the exact linear inverse.
  const auto locate = [&](const Vec3& world, const Vec3& from) {
    if (cell.affine) return inverse_map(cell, world, from);
    InverseMap m;
    m.p = from;
    m.converged = multilinear_newton(cell.multilinear, world, m.p, false, m.iterations);
    return m;
  };
  for (int k = 0; k + 1 < n_ts; ++k) {
    const double tm = 0.5 * (ts[k] + ts[k + 1]);
    const InverseMap m = locate(ray.origin + tm * ray.direction, start);
    if (!m.converged) {
      // Re-try from the centre before deciding: a warm start may sit in another cell's basin.
      const InverseMap m2 = locate(ray.origin + tm * ray.direction, linear_reference_centre(cell.type));
      if (!m2.converged) {
        failed = true;
        continue;
      }
      if (!inside_reference(cell.type, m2.p, 1e-9)) continue;
      start = m2.p;
    } else {
      if (!inside_reference(cell.type, m.p, 1e-9)) continue;
      start = m.p;
    }
    if (n_out > 0 && out[n_out - 1].t_far == ts[k])
      out[n_out - 1].t_far = ts[k + 1];
    else
      out[n_out++] = {ts[k], ts[k + 1], start};
  }
  return n_out;
}

Chord chord(const LinearCell& cell, const ViewRay& ray, const std::int64_t* global_ids) {
  Chord out;
  const RayFrame frame(ray);
  std::array<double, 2 * 6> ts{};  // at most 2 hits per face (a bilinear patch), 6 faces
  std::size_t n_ts = 0;
  for (int f = 0; f < linear_face_count(cell.type); ++f) {
    const FaceNodes face = linear_face(cell.type, f);
    std::array<Vec3, 4> cyclic{};
    std::array<std::int64_t, 4> ids{};
    for (int k = 0; k < face.count; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      cyclic[kk] = cell.x[static_cast<std::size_t>(face.node[kk])];
      if (global_ids != nullptr) ids[kk] = global_ids[face.node[kk]];
    }
    const std::array<int, 4> perm = global_ids != nullptr ? canonical_face_order(ids, face.count)
                                                         : canonical_face_order(cyclic, face.count);
    std::array<Vec3, 4> canonical{};
    for (int k = 0; k < face.count; ++k)
      canonical[static_cast<std::size_t>(k)] = cyclic[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])];
    const FaceHits hits = intersect_face(canonical, face.count, ray, frame);
    for (int h = 0; h < hits.count; ++h) {
      ts[n_ts++] = hits.hit[static_cast<std::size_t>(h)].t;
      out.hits.push_back({hits.hit[static_cast<std::size_t>(h)].t, f});
    }
  }
  std::sort(out.hits.begin(), out.hits.end(), [](const ChordFaceHit& a, const ChordFaceHit& b) {
    return a.t < b.t || (a.t == b.t && a.face < b.face);
  });
  std::sort(ts.begin(), ts.begin() + static_cast<std::ptrdiff_t>(n_ts));
  n_ts = static_cast<std::size_t>(std::unique(ts.begin(), ts.begin() + static_cast<std::ptrdiff_t>(n_ts)) - ts.begin());
  std::array<ChordInterval, 2 * 6> intervals{};
  const int n_iv = classify_chord_intervals(cell, ray, ts.data(), static_cast<int>(n_ts), intervals.data(), out.failed);
  out.intervals.assign(intervals.begin(), intervals.begin() + n_iv);
  return out;
}

}  // namespace rayint
