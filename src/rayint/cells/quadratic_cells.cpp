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
  switch (type) {
    case QuadraticCellType::tetra: return tetra;
    case QuadraticCellType::hexahedron: return hexahedron;
    case QuadraticCellType::wedge: return wedge;
  }
  return tetra;
}

double power(double x, int e) { return e == 0 ? 1.0 : (e == 1 ? x : x * x); }

// At most 20 entries, on the stack (the inverse map evaluates these in its Newton loop).
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 20, 1>;

}  // namespace

bool quadratic_cell_type_from_vtk(int vtk_id, QuadraticCellType& type) {
  if (vtk_id < 24 || vtk_id > 26) return false;
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
