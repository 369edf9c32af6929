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
  }
  return tetra;
}

double power(double x, int e) { return e == 0 ? 1.0 : (e == 1 ? x : x * x); }

// At most 27 entries, on the stack (the inverse map evaluates these in its Newton loop).
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 27, 1>;

}  // namespace

bool quadratic_cell_type_from_vtk(int vtk_id, QuadraticCellType& type) {
  if ((vtk_id < 24 || vtk_id > 26) && vtk_id != 29 && vtk_id != 32) return false;
  type = static_cast<QuadraticCellType>(vtk_id);
  return true;
}

int quadratic_node_count(QuadraticCellType type) { return static_cast<int>(basis(type).nodes.size()); }

const std::vector<Vec3>& quadratic_reference_nodes(QuadraticCellType type) { return basis(type).nodes; }

void quadratic_shape_functions(QuadraticCellType type, const Vec3& p, double* N) {
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
