// VTK's quadratic cells: nodes, shape functions, derivatives (see quadratic_cells.hpp).
#include "rayint/cells/quadratic_cells.hpp"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <stdexcept>

namespace rayint {
namespace {

using Exponents = std::array<int, 3>;

struct Basis {
  std::vector<Vec3> nodes;
  std::vector<Exponents> monomials;
  Eigen::MatrixXd inverse;  // V^-1: N_i(p) = sum_j m_j(p) inverse(j, i)
};

Basis make_basis(std::vector<Vec3> nodes, std::vector<Exponents> monomials) {
  const auto n = static_cast<Eigen::Index>(nodes.size());
  if (static_cast<Eigen::Index>(monomials.size()) != n) throw std::logic_error("quadratic cells: basis size");
  Eigen::MatrixXd V(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const Exponents& e = monomials[static_cast<std::size_t>(j)];
      const Vec3& x = nodes[static_cast<std::size_t>(i)];
      V(i, j) = std::pow(x[0], e[0]) * std::pow(x[1], e[1]) * std::pow(x[2], e[2]);
    }
  return {std::move(nodes), std::move(monomials), V.fullPivLu().inverse()};
}

const Basis& basis(QuadraticCellType type) {
  static const std::vector<Exponents> p2 = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                            {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  static const Basis tetra = make_basis(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}, {0, 0, 0.5}, {0.5, 0, 0.5},
       {0, 0.5, 0.5}},
      p2);
  static const Basis hexahedron = [] {
    std::vector<Exponents> m = p2;
    for (const Exponents& e : std::vector<Exponents>{{2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2},
                                                     {1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}})
      m.push_back(e);
    return make_basis({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
                       {0.5, 0, 0}, {1, 0.5, 0}, {0.5, 1, 0}, {0, 0.5, 0}, {0.5, 0, 1}, {1, 0.5, 1}, {0.5, 1, 1},
                       {0, 0.5, 1}, {0, 0, 0.5}, {1, 0, 0.5}, {1, 1, 0.5}, {0, 1, 0.5}},
                      m);
  }();
  static const Basis wedge = make_basis(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0},
       {0.5, 0, 1}, {0.5, 0.5, 1}, {0, 0.5, 1}, {0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5}},
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {2, 0, 1},
       {1, 1, 1}, {0, 2, 1}, {0, 0, 2}, {1, 0, 2}, {0, 1, 2}});
  // Triquadratic hexahedron: the 20 nodes above, then the face centres (x = 0, x = 1, y = 0, y = 1,
  // z = 0, z = 1: vtkTriQuadraticHexahedron.h's faces (0,4,7,3), (1,2,6,5), (0,1,5,4), (3,7,6,2),
  // (0,3,2,1), (4,5,6,7)) and the cell centre; the full tensor space Q2 = {r^a s^b t^c, a, b, c <= 2}.
  static const Basis hexahedron27 = [] {
    std::vector<Vec3> nodes = hexahedron.nodes;
    for (const Vec3& p : std::vector<Vec3>{{0, 0.5, 0.5}, {1, 0.5, 0.5}, {0.5, 0, 0.5}, {0.5, 1, 0.5}, {0.5, 0.5, 0},
                                           {0.5, 0.5, 1}, {0.5, 0.5, 0.5}})
      nodes.push_back(p);
    std::vector<Exponents> m;
    for (int a = 0; a <= 2; ++a)
      for (int b = 0; b <= 2; ++b)
        for (int c = 0; c <= 2; ++c) m.push_back({a, b, c});
    return make_basis(std::move(nodes), std::move(m));
  }();
  // Biquadratic-quadratic wedge: the 15 nodes above, then the centres of the quadrilateral faces
  // (0,1,4,3), (1,2,5,4), (2,0,3,5) (vtkBiQuadraticQuadraticWedge.h); P2 of the triangle x
  // {1, t, t^2}.
  static const Basis wedge18 = [] {
    std::vector<Vec3> nodes = wedge.nodes;
    for (const Vec3& p : std::vector<Vec3>{{0.5, 0, 0.5}, {0.5, 0.5, 0.5}, {0, 0.5, 0.5}}) nodes.push_back(p);
    std::vector<Exponents> m;
    for (const Exponents& e : std::vector<Exponents>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}, {0, 2, 0}})
      for (int c = 0; c <= 2; ++c) m.push_back({e[0], e[1], c});
    return make_basis(std::move(nodes), std::move(m));
  }();
  switch (type) {
    case QuadraticCellType::tetra: return tetra;
    case QuadraticCellType::hexahedron: return hexahedron;
    case QuadraticCellType::wedge: return wedge;
    case QuadraticCellType::triquadratic_hexahedron: return hexahedron27;
    case QuadraticCellType::biquadratic_wedge: return wedge18;
    case QuadraticCellType::pyramid: break;  // not a Vandermonde basis (pyramid_functions)
  }
  return tetra;
}

double power(double x, int e) { return e == 0 ? 1.0 : (e == 1 ? x : x * x); }

// The 27- and 18-node cells as products (header: the Vandermonde inverse of 27 monomials rounds
// to 1.4e-14, too coarse for the inverse map's 4e-15 step test). Per node: the 1-D Lagrange
// index of each coordinate (hexahedron) or the P2 triangle node and the t index (wedge), read
// off the node's reference point (coordinates in {0, 1/2, 1}).
struct ProductNode {
  int a = 0, b = 0, c = 0;  // hexahedron: indices in r, s, t; wedge: a = triangle node 0-5, c = t index
};
const std::vector<ProductNode>& product_nodes(QuadraticCellType type) {
  const auto make = [](QuadraticCellType t) {
    std::vector<ProductNode> out;
    for (const Vec3& x : basis(t).nodes) {
      ProductNode q;
      const int i = static_cast<int>(std::lround(2.0 * x[0])), j = static_cast<int>(std::lround(2.0 * x[1]));
      q.c = static_cast<int>(std::lround(2.0 * x[2]));
      if (t == QuadraticCellType::biquadratic_wedge) {
        // Triangle nodes (r, s) = (0,0) (1,0) (0,1) (1/2,0) (1/2,1/2) (0,1/2) as 0-5, in 2 x units.
        static const int tri[3][3] = {{0, 5, 2}, {3, 4, -1}, {1, -1, -1}};  // tri[2r][2s]
        q.a = tri[i][j];
      } else {
        q.a = i, q.b = j;
      }
      out.push_back(q);
    }
    return out;
  };
  static const std::vector<ProductNode> hexahedron27 = make(QuadraticCellType::triquadratic_hexahedron);
  static const std::vector<ProductNode> wedge18 = make(QuadraticCellType::biquadratic_wedge);
  return type == QuadraticCellType::biquadratic_wedge ? wedge18 : hexahedron27;
}

// N and, when dN is given, its derivatives (VTK's layout) of a 27- or 18-node cell.
void product_functions(QuadraticCellType type, const Vec3& p, double* N, double* dN) {
  const std::vector<ProductNode>& nodes = product_nodes(type);
  const auto n = static_cast<int>(nodes.size());
  double lr[3], dlr[3], ls[3], dls[3], lt[3], dlt[3];
  lagrange_1d(p[0], lr, dlr);
  lagrange_1d(p[1], ls, dls);
  lagrange_1d(p[2], lt, dlt);
  double T[6], Tr[6], Ts[6];
  if (type == QuadraticCellType::biquadratic_wedge) p2_triangle(p[0], p[1], T, Tr, Ts);
  for (int i = 0; i < n; ++i) {
    const ProductNode& q = nodes[static_cast<std::size_t>(i)];
    if (type == QuadraticCellType::biquadratic_wedge) {
      N[i] = T[q.a] * lt[q.c];
      if (dN) dN[i] = Tr[q.a] * lt[q.c], dN[n + i] = Ts[q.a] * lt[q.c], dN[2 * n + i] = T[q.a] * dlt[q.c];
    } else {
      N[i] = lr[q.a] * ls[q.b] * lt[q.c];
      if (dN)
        dN[i] = dlr[q.a] * ls[q.b] * lt[q.c], dN[n + i] = lr[q.a] * dls[q.b] * lt[q.c],
        dN[2 * n + i] = lr[q.a] * ls[q.b] * dlt[q.c];
    }
  }
}

// VTK's quadratic pyramid (vtkQuadraticPyramid::InterpolationFunctions, header), on any number
// type T (double, or Dual below for exact derivatives).
template <class T>
void pyramid_functions(const T& pr, const T& ps, const T& pt, T* w) {
  const T a = 2.0 * pr - 1.0, b = 2.0 * ps - 1.0, c = 2.0 * pt - 1.0;
  const T am = 1.0 - a, ap = 1.0 + a, bm = 1.0 - b, bp = 1.0 + b, cm = 1.0 - c;
  const T ab = a * b, ac = a * c, bc = b * c, abc = ab * c;
  w[0] = -(am * bm * cm * (4.0 + 3.0 * a + 3.0 * b + 2.0 * ab + 2.0 * c + ac + bc + 2.0 * abc)) / 16.0;
  w[1] = -(ap * bm * cm * (4.0 - 3.0 * a + 3.0 * b - 2.0 * ab + 2.0 * c - ac + bc - 2.0 * abc)) / 16.0;
  w[2] = -(ap * bp * cm * (4.0 - 3.0 * a - 3.0 * b + 2.0 * ab + 2.0 * c - ac - bc + 2.0 * abc)) / 16.0;
  w[3] = -(am * bp * cm * (4.0 + 3.0 * a - 3.0 * b - 2.0 * ab + 2.0 * c + ac - bc - 2.0 * abc)) / 16.0;
  w[4] = c * (1.0 + c) / 2.0;
  const T a2 = 1.0 - a * a, b2 = 1.0 - b * b, c2 = 1.0 - c * c;
  w[5] = a2 * bm * cm * (2.0 + b + bc) / 8.0;
  w[6] = ap * b2 * cm * (2.0 - a - ac) / 8.0;
  w[7] = a2 * bp * cm * (2.0 - b - bc) / 8.0;
  w[8] = am * b2 * cm * (2.0 + a + ac) / 8.0;
  w[9] = am * bm * c2 / 4.0;
  w[10] = ap * bm * c2 / 4.0;
  w[11] = ap * bp * c2 / 4.0;
  w[12] = am * bp * c2 / 4.0;
}

// A value and its gradient in (r, s, t): the pyramid's derivatives by the chain and product rules.
struct Dual {
  double v = 0.0;
  std::array<double, 3> g{};
  Dual() = default;
  Dual(double x) : v(x) {}  // NOLINT: constants enter the formula as duals
};
Dual operator+(const Dual& x, const Dual& y) {
  Dual o(x.v + y.v);
  for (std::size_t k = 0; k < 3; ++k) o.g[k] = x.g[k] + y.g[k];
  return o;
}
Dual operator-(const Dual& x, const Dual& y) {
  Dual o(x.v - y.v);
  for (std::size_t k = 0; k < 3; ++k) o.g[k] = x.g[k] - y.g[k];
  return o;
}
Dual operator-(const Dual& x) { return Dual(0.0) - x; }
Dual operator*(const Dual& x, const Dual& y) {
  Dual o(x.v * y.v);
  for (std::size_t k = 0; k < 3; ++k) o.g[k] = x.g[k] * y.v + x.v * y.g[k];
  return o;
}
Dual operator/(const Dual& x, double d) {
  Dual o(x.v / d);
  for (std::size_t k = 0; k < 3; ++k) o.g[k] = x.g[k] / d;
  return o;
}
Dual operator+(double x, const Dual& y) { return Dual(x) + y; }
Dual operator-(double x, const Dual& y) { return Dual(x) - y; }
Dual operator*(double x, const Dual& y) { return Dual(x) * y; }
Dual operator-(const Dual& x, double y) { return x - Dual(y); }

void pyramid_derivatives(const Vec3& p, double* dN) {
  Dual r(p[0]), s(p[1]), t(p[2]), w[13];
  r.g[0] = 1.0, s.g[1] = 1.0, t.g[2] = 1.0;
  pyramid_functions(r, s, t, w);
  for (int i = 0; i < 13; ++i)
    for (int k = 0; k < 3; ++k) dN[13 * k + i] = w[i].g[static_cast<std::size_t>(k)];
}

const std::vector<Vec3>& pyramid_nodes() {  // vtkQuadraticPyramid::GetParametricCoords
  static const std::vector<Vec3> nodes = {{0, 0, 0},   {1, 0, 0},   {1, 1, 0},   {0, 1, 0}, {0, 0, 1},
                                          {0.5, 0, 0}, {1, 0.5, 0}, {0.5, 1, 0}, {0, 0.5, 0},
                                          {0, 0, 0.5}, {1, 0, 0.5}, {1, 1, 0.5}, {0, 1, 0.5}};
  return nodes;
}

bool is_product(QuadraticCellType type) {
  return type == QuadraticCellType::triquadratic_hexahedron || type == QuadraticCellType::biquadratic_wedge;
}

// At most 27 entries, on the stack (the inverse map evaluates these in its Newton loop).
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 27, 1>;

}  // namespace

void lagrange_1d(double u, double* l, double* dl) {
  l[0] = 2.0 * (u - 0.5) * (u - 1.0), l[1] = 4.0 * u * (1.0 - u), l[2] = 2.0 * u * (u - 0.5);
  dl[0] = 4.0 * u - 3.0, dl[1] = 4.0 - 8.0 * u, dl[2] = 4.0 * u - 1.0;
}

void p2_triangle(double r, double s, double* N, double* dr, double* ds) {
  const double L[3] = {1.0 - r - s, r, s}, Lr[3] = {-1.0, 1.0, 0.0}, Ls[3] = {-1.0, 0.0, 1.0};
  for (int k = 0; k < 3; ++k) {
    N[k] = L[k] * (2.0 * L[k] - 1.0);
    dr[k] = (4.0 * L[k] - 1.0) * Lr[k];
    ds[k] = (4.0 * L[k] - 1.0) * Ls[k];
    const int i = k, j = (k + 1) % 3;
    N[3 + k] = 4.0 * L[i] * L[j];
    dr[3 + k] = 4.0 * (Lr[i] * L[j] + L[i] * Lr[j]);
    ds[3 + k] = 4.0 * (Ls[i] * L[j] + L[i] * Ls[j]);
  }
}

bool quadratic_cell_type_from_vtk(int vtk_id, QuadraticCellType& type) {
  if ((vtk_id < 24 || vtk_id > 27) && vtk_id != 29 && vtk_id != 32) return false;
  type = static_cast<QuadraticCellType>(vtk_id);
  return true;
}

int quadratic_node_count(QuadraticCellType type) { return static_cast<int>(quadratic_reference_nodes(type).size()); }

const std::vector<Vec3>& quadratic_reference_nodes(QuadraticCellType type) {
  return type == QuadraticCellType::pyramid ? pyramid_nodes() : basis(type).nodes;
}

void quadratic_shape_functions(QuadraticCellType type, const Vec3& p, double* N) {
  if (type == QuadraticCellType::pyramid) return pyramid_functions(p[0], p[1], p[2], N);
  if (is_product(type)) return product_functions(type, p, N, nullptr);
  const Basis& b = basis(type);
  const auto n = static_cast<Eigen::Index>(b.nodes.size());
  SmallVector m(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Exponents& e = b.monomials[static_cast<std::size_t>(j)];
    m(j) = power(p[0], e[0]) * power(p[1], e[1]) * power(p[2], e[2]);
  }
  SmallVector out(n);
  out.noalias() = b.inverse.transpose() * m;
  for (Eigen::Index i = 0; i < n; ++i) N[i] = out(i);
}

void quadratic_shape_derivatives(QuadraticCellType type, const Vec3& p, double* dN) {
  if (type == QuadraticCellType::pyramid) return pyramid_derivatives(p, dN);
  if (is_product(type)) {
    double N[27];
    return product_functions(type, p, N, dN);
  }
  const Basis& b = basis(type);
  const auto n = static_cast<Eigen::Index>(b.nodes.size());
  for (int axis = 0; axis < 3; ++axis) {
    SmallVector m(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const Exponents& e = b.monomials[static_cast<std::size_t>(j)];
      double v = 1.0;
      for (int k = 0; k < 3; ++k) {
        const auto ek = e[static_cast<std::size_t>(k)];
        if (k == axis) v *= ek == 0 ? 0.0 : (ek == 1 ? 1.0 : 2.0 * p[k]);
        else v *= power(p[k], ek);
      }
      m(j) = v;
    }
    SmallVector out(n);
    out.noalias() = b.inverse.transpose() * m;
    for (Eigen::Index i = 0; i < n; ++i) dN[axis * n + i] = out(i);
  }
}

}  // namespace rayint
