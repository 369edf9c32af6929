#pragma once
// Shape functions of the higher-order cells of Williams & Max (1992, appendix): the scalar in a
// cell is S_c = sum_i N_i(xi) s_i (appendix, last equation) with the node values s_i.
//   tet10: 10-node quadratic tetrahedron. Reference coordinates xi = (xi, eta, zeta) with
//          barycentrics L1 = 1 - xi - eta - zeta, L2 = xi, L3 = eta, L4 = zeta. Corner i:
//          N = L_i (2 L_i - 1); edge (i, j): N = 4 L_i L_j. Spans {1, x, y, z, x^2, xy, y^2,
//          yz, z^2, xz}, the appendix's 10-term parameter function.
//   hex8:  8-node trilinear brick on [-1, 1]^3: N = (1 + xi xi_i)(1 + eta eta_i)(1 + zeta
//          zeta_i) / 8. Spans {1, x, y, z, xy, yz, xz, xyz}.
//   hex20: 20-node quadratic serendipity brick on [-1, 1]^3. Corner: N = (1 + xi xi_i)(1 + eta
//          eta_i)(1 + zeta zeta_i)(xi xi_i + eta eta_i + zeta zeta_i - 2) / 8; mid-edge node
//          with xi_i = 0: N = (1 - xi^2)(1 + eta eta_i)(1 + zeta zeta_i) / 4 (likewise for the
//          other axes). Spans the appendix's 20 monomials, up to x^2yz, xy^2z, xyz^2.
// Node order is VTK's (VTK_QUADRATIC_TETRA, VTK_HEXAHEDRON, VTK_QUADRATIC_HEXAHEDRON), so that
// cells read from VTK files can use these directly.
//
// Every shape function is a product of factors linear in xi (the corner factor of hex20 too),
// which is how cells/cell.cpp turns them into exact polynomials along a ray.
//
// Degree along a straight ray (xi linear in the ray parameter): tet10 2, hex8 3 (the xyz term),
// hex20 4 (x^2yz and its kin; the "2 or 3" holds for tet10 and hex8 only). Rays parallel
// to a coordinate plane of a brick lower it (hex8 2, hex20 3), parallel to an axis further
// (hex8 1, hex20 2). Tests [cells]: partition of unity and nodal interpolation to 1e-15.
#include <array>
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

enum class CellType { tet10, hex8, hex20 };

const char* cell_type_name(CellType type);  // "tet10", "hex8", "hex20"
int node_count(CellType type);              // 10, 8, 20
int ray_degree(CellType type);              // 2, 3, 4 along a general ray
bool is_brick(CellType type);

// The nodes in reference coordinates, VTK order.
const std::vector<Vec3>& reference_nodes(CellType type);

// Factors of one shape function: N(xi) = scale * prod_k (c0_k + c1_k . xi).
struct LinearFactor {
  double c0 = 0.0;
  Vec3 c1 = Vec3::Zero();
};
struct ShapeProduct {
  double scale = 1.0;
  std::vector<LinearFactor> factors;
};
// The factored shape functions (one per node).
const std::vector<ShapeProduct>& shape_products(CellType type);

// N_i(xi) for every node, evaluated from the formulas above (not from the products).
std::vector<double> shape_functions(CellType type, const Vec3& xi);

}  // namespace rayint
