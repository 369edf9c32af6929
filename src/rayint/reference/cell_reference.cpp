// The 50-digit reference for the ray integral through one linear cell in its own interpolation.
//
// What it computes: see cell_reference.hpp. Light enters the chord at t_far and leaves at t_near
// (toward the eye); with pieces k ordered near -> far, emission = sum_k exp(-D_{<k}) E_k and
// depth = sum_k D_k, where on a piece [a, b] (world length element |d| dt)
//   D_k = int_a^b rho(f(t)) |d| dt,  E_k = int_a^b kappa rho exp(-int_a^t rho |d|) |d| dt.
//
// Methods (all in cpp_bin_float_50, 168-bit significand):
//   - Inverse map: Newton on x(p) = x, 3x3 steps by Cramer's rule, from the previous point (the
//     domain's centroid first), steps capped at 0.5, converged when the step is below 1e-46
//     (budget 60 steps; else std::runtime_error). df/dt = grad_p f . J^-1 d at the solution.
//   - Critical points: df/dt at 49 equally spaced points of the chord; each sign change refined by
//     TOMS 748 on df/dt to 160 bits. Breakpoint crossings: every breakpoint strictly between the
//     values at the ends of a monotone stretch, TOMS 748 on f - b to 160 bits. (Two critical
//     points closer than chord / 48 would be missed, as in any sampling; the series check
//     below then fails to converge near the kink and the reference throws rather than guess.)
//   - Each piece: a Chebyshev series of f on its Chebyshev-Lobatto points, degree 16, 32, ...,
//     512, until |c_{n-1}| + |c_n| <= 1e-42 * max|f_i| and the series matches a direct
//     evaluation at 7 interior points to 1e-40 * max|f_i|; e_f = the larger of the two.
//   - rho and kappa are linear in f on a piece (Sec. 3.1), so rho is a series and tau its exact
//     antiderivative; E_k by composite 61-point Gauss-Kronrod, ceil(D_k / 18) subintervals (the
//     61-point limit of reference.cpp), doubled until sum |K - G| <= 1e-36 * E_k (budget 8).
// Error bound per channel: quadrature estimate + propagated e_f (slopes times e_f times length,
// as cells/cell_integral.hpp) + rounding (1e-44 relative); its bound is <= 1e-30 of the value
// (checked). Accuracy: tests [cells][isoparametric] check it, rounded to double, against
// reference_ray (reference.cpp, different code) on chords along which the scalar is exactly
// linear (axis-parallel rays with dyadic data through a tetra, hexahedron, voxel and wedge):
// equal within 1e-15 relative, i.e. to double rounding.
#include "rayint/reference/cell_reference.hpp"

#include <algorithm>
#include <boost/math/constants/constants.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "rayint/reference/reference_detail.hpp"

namespace rayint {
namespace {

using reference_detail::LinearPart;
using reference_detail::linear_part;
using reference_detail::Real;
using R3 = std::array<Real, 3>;

constexpr int kMaxNodes = 27;

int node_count(int id) {
  switch (id) {
    case 10: return 4;
    case 11: case 12: return 8;
    case 13: return 6;
    case 14: return 5;
    case 24: return 10;
    case 25: return 20;
    case 26: return 15;
    case 27: return 13;
    case 29: return 27;
    case 32: return 18;
    default: return 0;
  }
}

// A value with its gradient in (r, s, t): the quadratic cells' shape functions are written as
// products of their textbook factors and differentiated by the product rule, here, in 50 digits
// (not the Vandermonde construction of cells/quadratic_cells.cpp).
struct Dual {
  Real v;
  R3 g{Real(0), Real(0), Real(0)};
};
Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, {a.g[0] + b.g[0], a.g[1] + b.g[1], a.g[2] + b.g[2]}}; }
Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, {a.g[0] - b.g[0], a.g[1] - b.g[1], a.g[2] - b.g[2]}}; }
Dual operator*(const Dual& a, const Dual& b) {
  return {a.v * b.v, {a.g[0] * b.v + a.v * b.g[0], a.g[1] * b.v + a.v * b.g[1], a.g[2] * b.v + a.v * b.g[2]}};
}
Dual operator*(const Real& c, const Dual& a) { return {c * a.v, {c * a.g[0], c * a.g[1], c * a.g[2]}}; }
Dual constant(const Real& c) { return {c}; }
Dual coordinate(const R3& p, int k) {
  Dual d{p[static_cast<std::size_t>(k)]};
  d.g[static_cast<std::size_t>(k)] = 1;
  return d;
}

// The quadratic Lagrange functions of one coordinate on the nodes 0, 1/2, 1.
void lagrange_1d(const Dual& x, Dual* l) {
  const Dual one = constant(Real(1)), half = constant(Real(0.5));
  l[0] = Real(2) * ((x - half) * (x - one));
  l[1] = Real(4) * (x * (one - x));
  l[2] = Real(2) * (x * (x - half));
}

// VTK's quadratic cells (vtkQuadraticTetra, vtkQuadraticHexahedron, vtkQuadraticWedge,
// vtkTriQuadraticHexahedron, vtkBiQuadraticQuadraticWedge): the textbook serendipity / P2 /
// Lagrange shape functions on VTK's parametric nodes, VTK's node order.
void quadratic_shape(int id, const R3& p, Dual* N) {
  const Dual one = constant(Real(1)), r = coordinate(p, 0), s = coordinate(p, 1), t = coordinate(p, 2);
  switch (id) {
    case 24: {  // barycentric L; corner L (2L - 1), edge 4 La Lb, edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3)
      const Dual L[4] = {one - r - s - t, r, s, t};
      static const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
      for (int i = 0; i < 4; ++i) N[i] = L[i] * (Real(2) * L[i] - one);
      for (int e = 0; e < 6; ++e) N[4 + e] = Real(4) * (L[edges[e][0]] * L[edges[e][1]]);
      return;
    }
    case 25: {  // on (xi, eta, zeta) = 2 p - 1; nodes at xi_i in {-1, 0, 1}
      static const int node[20][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1},
                                      {1, 1, 1},    {-1, 1, 1},  {0, -1, -1}, {1, 0, -1},  {0, 1, -1},  {-1, 0, -1},
                                      {0, -1, 1},   {1, 0, 1},   {0, 1, 1},   {-1, 0, 1},  {-1, -1, 0}, {1, -1, 0},
                                      {1, 1, 0},    {-1, 1, 0}};
      const Dual x[3] = {Real(2) * r - one, Real(2) * s - one, Real(2) * t - one};
      for (int i = 0; i < 20; ++i) {
        Dual prod = one, sum = constant(Real(-2));
        int zero = -1;
        for (int k = 0; k < 3; ++k) {
          if (node[i][k] == 0) {
            zero = k;
            continue;
          }
          const Dual a = Real(node[i][k]) * x[k];
          prod = prod * (one + a);
          sum = sum + a;
        }
        N[i] = zero < 0 ? Real(0.125) * (prod * sum) : Real(0.25) * (prod * (one - x[zero] * x[zero]));
      }
      return;
    }
    case 26: {  // L = (1 - r - s, r, s), z = 2t - 1
      const Dual L[3] = {one - r - s, r, s};
      const Dual z = Real(2) * t - one, bottom = one - z, top = one + z, bubble = one - z * z;
      for (int i = 0; i < 3; ++i) {
        const Dual corner = Real(0.5) * (L[i] * (Real(2) * L[i] - one));
        N[i] = corner * bottom - Real(0.5) * (L[i] * bubble);
        N[3 + i] = corner * top - Real(0.5) * (L[i] * bubble);
        const Dual edge = Real(2) * (L[i] * L[(i + 1) % 3]);
        N[6 + i] = edge * bottom;
        N[9 + i] = edge * top;
        N[12 + i] = L[i] * bubble;
      }
      return;
    }
    case 29: {  // Lagrange l_a(r) l_b(s) l_c(t), nodes at the grid points (a, b, c) / 2
      static const int node[27][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2},
                                      {0, 2, 2}, {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2},
                                      {1, 2, 2}, {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}, {0, 1, 1},
                                      {2, 1, 1}, {1, 0, 1}, {1, 2, 1}, {1, 1, 0}, {1, 1, 2}, {1, 1, 1}};
      Dual l[3][3];
      const Dual x[3] = {r, s, t};
      for (int k = 0; k < 3; ++k) lagrange_1d(x[k], l[k]);
      for (int i = 0; i < 27; ++i) N[i] = l[0][node[i][0]] * l[1][node[i][1]] * l[2][node[i][2]];
      return;
    }
    case 32: {  // P2 triangle (corners 0-2, edges (0,1) (1,2) (2,0)) times Lagrange in t
      const Dual L[3] = {one - r - s, r, s};
      Dual tri[6], lt[3];
      for (int i = 0; i < 3; ++i) {
        tri[i] = L[i] * (Real(2) * L[i] - one);
        tri[3 + i] = Real(4) * (L[i] * L[(i + 1) % 3]);
      }
      lagrange_1d(t, lt);
      // Node i: triangle node, level in t (0, 1/2, 1 as 0, 1, 2).
      static const int node[18][2] = {{0, 0}, {1, 0}, {2, 0}, {0, 2}, {1, 2}, {2, 2}, {3, 0}, {4, 0}, {5, 0},
                                      {3, 2}, {4, 2}, {5, 2}, {0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 1}};
      for (int i = 0; i < 18; ++i) N[i] = tri[node[i][0]] * lt[node[i][1]];
      return;
    }
    case 27: {  // vtkQuadraticPyramid: on (a, b, c) = 2 p - 1, corners (0,0) (1,0) (1,1) (0,1) of
                // the base as signs (-1,-1) (1,-1) (1,1) (-1,1) of (a, b), the apex, then mid-edge nodes
                // of the base's edges and of the four edges to the apex. VTK's formulas, factored:
                // corner k: -(1 + sa a)(1 + sb b)(1 - c)(4 - 3 sa a - 3 sb b + 2 sa sb a b + 2c
                //                                       - sa a c - sb b c + 2 sa sb a b c) / 16.
      const Dual a = Real(2) * r - one, b = Real(2) * s - one, c = Real(2) * t - one;
      static const int corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      const Dual cm = one - c;
      for (int k = 0; k < 4; ++k) {
        const Dual A = Real(corner[k][0]) * a, B = Real(corner[k][1]) * b;  // sa a, sb b
        const Dual inner = constant(Real(4)) - Real(3) * A - Real(3) * B + Real(2) * (A * B) + Real(2) * c - A * c -
                           B * c + Real(2) * (A * B * c);
        N[k] = Real(-1) / 16 * ((one + A) * (one + B) * cm * inner);
      }
      N[4] = Real(0.5) * (c * (one + c));
      // Base edges: (0,1) b = -1, (1,2) a = +1, (2,3) b = +1, (3,0) a = -1.
      const Dual a2 = one - a * a, b2 = one - b * b;
      for (int k = 0; k < 4; ++k) {
        const Real side(k == 0 || k == 3 ? -1 : 1);
        if (k % 2 == 0) {  // along a, at b = side
          const Dual B = side * b;
          N[5 + k] = Real(1) / 8 * (a2 * (one + B) * cm * (constant(Real(2)) - B - B * c));
        } else {           // along b, at a = side
          const Dual A = side * a;
          N[5 + k] = Real(1) / 8 * (b2 * (one + A) * cm * (constant(Real(2)) - A - A * c));
        }
      }
      const Dual c2 = one - c * c;
      for (int k = 0; k < 4; ++k)
        N[9 + k] = Real(0.25) * ((one + Real(corner[k][0]) * a) * (one + Real(corner[k][1]) * b) * c2);
      return;
    }
    default: throw std::invalid_argument("reference_cell_chord: unknown cell type");
  }
}

// N_i and dN_i/dp_j (dN[j][i]) of VTK's linear cells, from their documented definitions.
void shape(int id, const R3& p, Real* N, Real (*dN)[kMaxNodes]) {
  if (id >= 24) {
    Dual q[kMaxNodes];
    quadratic_shape(id, p, q);
    for (int i = 0; i < node_count(id); ++i) {
      N[i] = q[i].v;
      for (std::size_t j = 0; j < 3; ++j) dN[j][i] = q[i].g[j];
    }
    return;
  }
  const Real &r = p[0], &s = p[1], &t = p[2];
  const Real one(1);
  const Real rm = one - r, sm = one - s, tm = one - t;
  switch (id) {
    case 10:
      N[0] = one - r - s - t, N[1] = r, N[2] = s, N[3] = t;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 4; ++i) dN[j][i] = (i == 0) ? Real(-1) : Real(i == j + 1 ? 1 : 0);
      return;
    case 11:
    case 12: {
      // Hexahedron corners in VTK order as (bit r, bit s, bit t); voxel: node index bits x, y, z.
      static const int hex_bits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      for (int i = 0; i < 8; ++i) {
        int b[3];
        for (int k = 0; k < 3; ++k) b[k] = id == 12 ? hex_bits[i][k] : (i >> k) & 1;
        const Real fr = b[0] ? r : rm, fs = b[1] ? s : sm, ft = b[2] ? t : tm;
        const Real gr = b[0] ? one : Real(-1), gs = b[1] ? one : Real(-1), gt = b[2] ? one : Real(-1);
        N[i] = fr * fs * ft;
        dN[0][i] = gr * fs * ft;
        dN[1][i] = fr * gs * ft;
        dN[2][i] = fr * fs * gt;
      }
      return;
    }
    case 13: {
      const Real w = one - r - s;
      const Real base[3] = {w, r, s};
      const Real dbase_dr[3] = {Real(-1), one, Real(0)}, dbase_ds[3] = {Real(-1), Real(0), one};
      for (int i = 0; i < 3; ++i) {
        N[i] = base[i] * tm, N[i + 3] = base[i] * t;
        dN[0][i] = dbase_dr[i] * tm, dN[0][i + 3] = dbase_dr[i] * t;
        dN[1][i] = dbase_ds[i] * tm, dN[1][i + 3] = dbase_ds[i] * t;
        dN[2][i] = -base[i], dN[2][i + 3] = base[i];
      }
      return;
    }
    case 14: {
      const Real q[4] = {rm * sm, r * sm, r * s, rm * s};
      const Real dq_dr[4] = {-sm, sm, s, -s}, dq_ds[4] = {-rm, -r, r, rm};
      for (int i = 0; i < 4; ++i) {
        N[i] = q[i] * tm;
        dN[0][i] = dq_dr[i] * tm, dN[1][i] = dq_ds[i] * tm, dN[2][i] = -q[i];
      }
      N[4] = t, dN[0][4] = 0, dN[1][4] = 0, dN[2][4] = one;
      return;
    }
    default: throw std::invalid_argument("reference_cell_chord: unknown cell type");
  }
}

Real det3(const R3& a, const R3& b, const R3& c) {  // det [a b c] (columns)
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1]) +
         c[0] * (a[1] * b[2] - a[2] * b[1]);
}

R3 cramer(const R3& c0, const R3& c1, const R3& c2, const R3& rhs) {  // [c0 c1 c2] x = rhs
  const Real d = det3(c0, c1, c2);
  if (d == 0) throw std::runtime_error("reference_cell_chord: singular Jacobian");
  return {det3(rhs, c1, c2) / d, det3(c0, rhs, c2) / d, det3(c0, c1, rhs) / d};
}

class Cell {
 public:
  Cell(const CellReferenceInput& in) : id_(in.vtk_id), n_(node_count(in.vtk_id)) {
    if (n_ == 0) throw std::invalid_argument("reference_cell_chord: vtk_id must be 10..14, 24..27, 29 or 32");
    if (static_cast<int>(in.nodes.size()) != n_ || static_cast<int>(in.values.size()) != n_)
      throw std::invalid_argument("reference_cell_chord: node and value counts do not match the type");
    for (int i = 0; i < n_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      for (int j = 0; j < 3; ++j) {
        if (!std::isfinite(in.nodes[k][static_cast<std::size_t>(j)]))
          throw std::invalid_argument("reference_cell_chord: node coordinates must be finite");
        x_[i][j] = in.nodes[k][static_cast<std::size_t>(j)];
      }
      if (!std::isfinite(in.values[k])) throw std::invalid_argument("reference_cell_chord: values must be finite");
      f_[i] = in.values[k];
      scale_ = std::max(scale_, std::abs(in.values[k]));
    }
    for (int j = 0; j < 3; ++j) {
      const double o = in.origin[static_cast<std::size_t>(j)], d = in.direction[static_cast<std::size_t>(j)];
      if (!std::isfinite(o) || !std::isfinite(d))
        throw std::invalid_argument("reference_cell_chord: ray must be finite");
      o_[static_cast<std::size_t>(j)] = o;
      d_[static_cast<std::size_t>(j)] = d;
    }
    speed_ = sqrt(d_[0] * d_[0] + d_[1] * d_[1] + d_[2] * d_[2]);
    if (scale_ == 0) scale_ = 1;
    start_ = (id_ == 10 || id_ == 24) ? R3{Real(0.25), Real(0.25), Real(0.25)}
             : (id_ == 13 || id_ == 26 || id_ == 32) ? R3{Real(1) / 3, Real(1) / 3, Real(0.5)}
             : (id_ == 14 || id_ == 27) ? R3{Real(0.5), Real(0.5), Real(0.25)}
                         : R3{Real(0.5), Real(0.5), Real(0.5)};
  }

  // f and df/dt at ray parameter t.
  void eval(const Real& t, Real& f, Real* dfdt = nullptr) {
    ++evaluations;
    R3 target;
    for (std::size_t j = 0; j < 3; ++j) target[j] = o_[j] + t * d_[j];
    R3 p = start_;
    Real N[kMaxNodes], dN[3][kMaxNodes];
    R3 J[3];
    const Real step_tolerance("1e-46");
    for (int it = 0;; ++it) {
      if (it == 60) throw std::runtime_error("reference_cell_chord: Newton missed 1e-46 in 60 steps");
      shape(id_, p, N, dN);
      R3 residual = target;
      for (int j = 0; j < 3; ++j) J[j] = {Real(0), Real(0), Real(0)};
      for (int i = 0; i < n_; ++i)
        for (std::size_t k = 0; k < 3; ++k) {
          residual[k] -= N[i] * x_[i][k];
          for (int j = 0; j < 3; ++j) J[j][k] += dN[j][i] * x_[i][k];
        }
      R3 step = cramer(J[0], J[1], J[2], residual);
      Real size = std::max({abs(step[0]), abs(step[1]), abs(step[2])});
      if (size > Real(0.5))
        for (Real& s : step) s *= Real(0.5) / size;
      for (std::size_t k = 0; k < 3; ++k) p[k] += step[k];
      if (size <= step_tolerance) break;
    }
    start_ = p;
    shape(id_, p, N, dN);
    f = 0;
    R3 grad{Real(0), Real(0), Real(0)};
    for (int i = 0; i < n_; ++i) {
      f += N[i] * f_[i];
      for (std::size_t j = 0; j < 3; ++j) grad[j] += dN[j][i] * f_[i];
    }
    if (dfdt != nullptr) {
      for (int j = 0; j < 3; ++j) J[j] = {Real(0), Real(0), Real(0)};
      for (int i = 0; i < n_; ++i)
        for (std::size_t k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) J[j][k] += dN[j][i] * x_[i][k];
      const R3 q = cramer(J[0], J[1], J[2], d_);
      *dfdt = grad[0] * q[0] + grad[1] * q[1] + grad[2] * q[2];
    }
  }

  const Real& speed() const { return speed_; }
  double scale() const { return scale_; }
  int evaluations = 0;

 private:
  int id_, n_;
  Real x_[kMaxNodes][3];
  Real f_[kMaxNodes];
  R3 o_, d_, start_;
  Real speed_;
  double scale_ = 0.0;
};

Real clenshaw(const std::vector<Real>& c, const Real& x) {
  Real b1 = 0, b2 = 0;
  for (std::size_t k = c.size(); k-- > 1;) {
    Real b0 = 2 * x * b1 - b2 + c[k];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + c[0];
}

std::vector<Real> antiderivative(const std::vector<Real>& c) {
  const std::size_t n = c.size() - 1;
  std::vector<Real> C(n + 2, Real(0));
  auto at = [&](std::size_t k) { return k <= n ? c[k] : Real(0); };
  C[1] = c[0] - at(2) / 2;
  for (std::size_t k = 2; k <= n + 1; ++k) C[k] = (at(k - 1) - at(k + 1)) / (2 * static_cast<int>(k));
  return C;
}

struct Series {
  std::vector<Real> c;
  Real error;  // e_f
};

// Chebyshev series of f on [a, b] (x in [-1, 1]), degree doubled until tail and check pass.
Series piece_series(Cell& cell, const Real& a, const Real& b, int& max_degree) {
  const Real pi = boost::math::constants::pi<Real>();
  const Real mid = (a + b) / 2, half = (b - a) / 2;
  const Real tail_target = Real("1e-42") * cell.scale(), check_target = Real("1e-40") * cell.scale();
  std::vector<Real> v;
  for (int n = 16; n <= 512; n *= 2) {
    std::vector<Real> w(static_cast<std::size_t>(n) + 1);
    for (int j = 0; j <= n; ++j) {
      if (j % 2 == 0 && !v.empty()) {
        w[static_cast<std::size_t>(j)] = v[static_cast<std::size_t>(j / 2)];
        continue;
      }
      cell.eval(mid + half * cos(pi * j / n), w[static_cast<std::size_t>(j)]);
    }
    v.swap(w);
    std::vector<Real> cosine(2 * static_cast<std::size_t>(n));
    for (int m = 0; m < 2 * n; ++m) cosine[static_cast<std::size_t>(m)] = cos(pi * m / n);
    Series s;
    s.c.assign(static_cast<std::size_t>(n) + 1, Real(0));
    for (int k = 0; k <= n; ++k) {
      Real sum = (v[0] + ((k % 2 == 0) ? v[static_cast<std::size_t>(n)] : -v[static_cast<std::size_t>(n)])) / 2;
      for (int j = 1; j < n; ++j) sum += v[static_cast<std::size_t>(j)] * cosine[static_cast<std::size_t>((j * k) % (2 * n))];
      s.c[static_cast<std::size_t>(k)] = 2 * sum / n;
    }
    s.c[0] /= 2;
    s.c[static_cast<std::size_t>(n)] /= 2;
    const Real tail = abs(s.c[static_cast<std::size_t>(n) - 1]) + abs(s.c[static_cast<std::size_t>(n)]);
    if (tail > tail_target) continue;
    Real worst = 0;
    for (int k = 0; k < 7; ++k) {
      const Real x = cos(pi * (Real(k) + Real("0.3719")) / 7);
      Real f;
      cell.eval(mid + half * x, f);
      worst = std::max(worst, abs(clenshaw(s.c, x) - f));
    }
    if (worst > check_target) continue;
    s.error = std::max(tail, worst);
    max_degree = std::max(max_degree, n);
    return s;
  }
  throw std::runtime_error("reference_cell_chord: Chebyshev series missed 1e-42 at degree 512");
}

template <class F>
Real solve(F g, const Real& lo, const Real& hi, const Real& g_lo, const Real& g_hi) {
  boost::math::tools::eps_tolerance<Real> tol(160);
  std::uintmax_t iterations = 300;
  const auto r = boost::math::tools::toms748_solve(g, lo, hi, g_lo, g_hi, tol, iterations);
  return (r.first + r.second) / 2;
}

}  // namespace

CellReference reference_cell_chord(const TransferFunctions& tf, const CellReferenceInput& input) {
  reference_detail::check_transfer_functions(tf);
  if (!(std::isfinite(input.t_near) && std::isfinite(input.t_far) && input.t_far >= input.t_near))
    throw std::invalid_argument("reference_cell_chord: chord ends must be finite, t_near <= t_far");
  Cell cell(input);
  CellReference out;
  if (input.t_far == input.t_near) return out;
  const Real a = input.t_near, b = input.t_far;

  // Critical points of f on the true scalar.
  constexpr int kSamples = 48;
  std::vector<Real> monotone{a};
  Real t_prev = a, f_prev, d_prev;
  cell.eval(a, f_prev, &d_prev);
  for (int k = 1; k <= kSamples; ++k) {
    const Real t = a + (b - a) * k / kSamples;
    Real f, d;
    cell.eval(t, f, &d);
    if (d == 0 && k < kSamples) {
      monotone.push_back(t);
    } else if (d_prev != 0 && d != 0 && (d < 0) != (d_prev < 0)) {
      monotone.push_back(solve(
          [&](const Real& s) {
            Real fs, ds;
            cell.eval(s, fs, &ds);
            return ds;
          },
          t_prev, t, d_prev, d));
    }
    t_prev = t;
    d_prev = d;
  }
  monotone.push_back(b);
  // Breakpoint crossings on each monotone stretch.
  std::vector<Real> levels;
  for (double v : tf.breakpoints()) levels.emplace_back(v);
  std::vector<Real> knots;
  for (std::size_t k = 0; k + 1 < monotone.size(); ++k) {
    const Real &lo = monotone[k], &hi = monotone[k + 1];
    if (!(hi > lo)) continue;
    knots.push_back(lo);
    Real f_lo, f_hi;
    cell.eval(lo, f_lo);
    cell.eval(hi, f_hi);
    for (const Real& level : levels)
      if (level > std::min(f_lo, f_hi) && level < std::max(f_lo, f_hi))
        knots.push_back(solve(
            [&](const Real& s) {
              Real fs;
              cell.eval(s, fs);
              return fs - level;
            },
            lo, hi, f_lo - level, f_hi - level));
  }
  knots.push_back(b);
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());

  const reference_detail::GaussKronrodRule rule = reference_detail::gauss_kronrod_rule(61);
  const Real target("1e-36"), rounding("1e-44");
  std::array<Real, kChannels> emission{}, depth{}, e_error{}, d_error{};
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {  // near -> far
    const Real &ta = knots[k], &tb = knots[k + 1];
    if (!(tb > ta)) continue;
    const Series s = piece_series(cell, ta, tb, out.max_degree);
    const Real h = (tb - ta) / 2 * cell.speed();  // world length per unit x
    const Real f_mid = clenshaw(s.c, Real(0));
    ++out.pieces;
    for (std::size_t c = 0; c < kChannels; ++c) {
      const LinearPart rho = linear_part(tf.density[c], f_mid), kappa = linear_part(tf.color[c], f_mid);
      std::vector<Real> r(s.c.size());
      for (std::size_t j = 0; j < r.size(); ++j) r[j] = rho.beta * s.c[j];
      r[0] = rho.v0 + rho.beta * (s.c[0] - rho.s0);
      const std::vector<Real> R = antiderivative(r);
      const Real R0 = clenshaw(R, Real(-1));
      const Real D = h * (clenshaw(R, Real(1)) - R0);
      Real E = 0, E_estimate = 0;
      if (rho.max_value > 0 && kappa.max_value > 0) {
        auto integrand = [&](const Real& x) {
          const Real f = clenshaw(s.c, x);
          return (kappa.v0 + kappa.beta * (f - kappa.s0)) * (rho.v0 + rho.beta * (f - rho.s0)) *
                 exp(-h * (clenshaw(R, x) - R0));
        };
        int n_sub = std::max(1, static_cast<int>(std::ceil(static_cast<double>(D) / 18.0)));
        for (int doubling = 0;; ++doubling) {
          const Real w = Real(1) / n_sub;  // half-width of a subinterval of [-1, 1]
          Real K_sum = 0, estimate = 0;
          for (int m = 0; m < n_sub; ++m) {
            const Real centre = -1 + w * (2 * m + 1);
            const reference_detail::GaussKronrodSums panel = reference_detail::gauss_kronrod_panel(rule, integrand, centre, w);
            K_sum += w * panel.kronrod;
            estimate += w * abs(panel.kronrod - panel.gauss);
          }
          E = h * K_sum;
          E_estimate = h * estimate;
          if (E_estimate <= target * abs(E)) break;
          if (doubling == 8) throw std::runtime_error("reference_cell_chord: quadrature missed 1e-36 after 8 doublings");
          n_sub *= 2;
        }
      }
      const Real length = h * 2;
      const Real attenuation = exp(-depth[c]);
      const Real dD = abs(rho.beta) * s.error * length;
      e_error[c] += attenuation * (E_estimate + length * s.error * (abs(kappa.beta) * rho.max_value +
                                                                   kappa.max_value * abs(rho.beta)) +
                                   E * dD + rounding * E);
      d_error[c] += dD + rounding * abs(D);
      emission[c] += attenuation * E;
      depth[c] += D;
    }
  }
  for (std::size_t c = 0; c < kChannels; ++c) {
    out.emission[c] = static_cast<double>(emission[c]);
    out.optical_depth[c] = static_cast<double>(depth[c]);
    // Rounding to double adds half an ulp: the bound is rounded up.
    out.emission_error[c] = reference_detail::rounded_up(e_error[c]);
    out.depth_error[c] = reference_detail::rounded_up(d_error[c]);
  }
  out.evaluations = cell.evaluations;
  return out;
}

}  // namespace rayint
