// Shape functions of the tet10, hex8 and hex20 cells (formulas and node order in
// shape_functions.hpp).
#include "rayint/cells/shape_functions.hpp"

#include <stdexcept>

namespace rayint {

namespace {

std::vector<Vec3> tet10_nodes() {
  const Vec3 c[4] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::vector<Vec3> n(c, c + 4);
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges) n.push_back(0.5 * (c[e[0]] + c[e[1]]));
  return n;
}

const int kHexEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

std::vector<Vec3> hex_nodes(bool serendipity) {
  std::vector<Vec3> n = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(-1, 1, -1),
                         Vec3(-1, -1, 1),  Vec3(1, -1, 1),  Vec3(1, 1, 1),  Vec3(-1, 1, 1)};
  if (serendipity)
    for (const auto& e : kHexEdges) n.push_back(0.5 * (n[e[0]] + n[e[1]]));
  return n;
}

// Barycentric L_i of the reference tetrahedron as linear factors.
LinearFactor barycentric(int i) {
  if (i == 0) return {1.0, Vec3(-1, -1, -1)};
  Vec3 c = Vec3::Zero();
  c[i - 1] = 1.0;
  return {0.0, c};
}

std::vector<ShapeProduct> tet10_products() {
  std::vector<ShapeProduct> p;
  for (int i = 0; i < 4; ++i) {  // L_i (2 L_i - 1)
    const LinearFactor L = barycentric(i);
    p.push_back({1.0, {L, {2.0 * L.c0 - 1.0, 2.0 * L.c1}}});
  }
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges) p.push_back({4.0, {barycentric(e[0]), barycentric(e[1])}});
  return p;
}

// 1 + xi_axis * sign
LinearFactor side(int axis, double sign) {
  Vec3 c = Vec3::Zero();
  c[axis] = sign;
  return {1.0, c};
}

std::vector<ShapeProduct> hex_products(bool serendipity) {
  const std::vector<Vec3> nodes = hex_nodes(serendipity);
  std::vector<ShapeProduct> p;
  for (int i = 0; i < 8; ++i) {
    const Vec3& x = nodes[i];
    ShapeProduct s{0.125, {side(0, x[0]), side(1, x[1]), side(2, x[2])}};
    if (serendipity) s.factors.push_back({-2.0, x});  // xi.xi_i - 2
    p.push_back(s);
  }
  if (serendipity)
    for (int i = 8; i < 20; ++i) {
      const Vec3& x = nodes[i];
      ShapeProduct s{0.25, {}};
      for (int a = 0; a < 3; ++a) {
        if (x[a] == 0.0) {  // (1 - xi_a)(1 + xi_a)
          s.factors.push_back(side(a, -1.0));
          s.factors.push_back(side(a, 1.0));
        } else {
          s.factors.push_back(side(a, x[a]));
        }
      }
      p.push_back(s);
    }
  return p;
}

}  // namespace

const char* cell_type_name(CellType type) {
  switch (type) {
    case CellType::tet10: return "tet10";
    case CellType::hex8: return "hex8";
    case CellType::hex20: return "hex20";
  }
  return "?";
}

int node_count(CellType type) {
  return type == CellType::tet10 ? 10 : type == CellType::hex8 ? 8 : 20;
}

int ray_degree(CellType type) {
  return type == CellType::tet10 ? 2 : type == CellType::hex8 ? 3 : 4;
}

bool is_brick(CellType type) { return type != CellType::tet10; }

const std::vector<Vec3>& reference_nodes(CellType type) {
  static const std::vector<Vec3> tet = tet10_nodes(), hex8 = hex_nodes(false),
                                  hex20 = hex_nodes(true);
  return type == CellType::tet10 ? tet : type == CellType::hex8 ? hex8 : hex20;
}

const std::vector<ShapeProduct>& shape_products(CellType type) {
  static const std::vector<ShapeProduct> tet = tet10_products(), hex8 = hex_products(false),
                                         hex20 = hex_products(true);
  return type == CellType::tet10 ? tet : type == CellType::hex8 ? hex8 : hex20;
}

std::vector<double> shape_functions(CellType type, const Vec3& xi) {
  std::vector<double> N;
  const double x = xi[0], y = xi[1], z = xi[2];
  if (type == CellType::tet10) {
    const double L[4] = {1.0 - x - y - z, x, y, z};
    for (int i = 0; i < 4; ++i) N.push_back(L[i] * (2.0 * L[i] - 1.0));
    const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (const auto& e : edges) N.push_back(4.0 * L[e[0]] * L[e[1]]);
    return N;
  }
  const std::vector<Vec3>& nodes = reference_nodes(type);
  for (int i = 0; i < 8; ++i) {
    const Vec3& n = nodes[i];
    const double trilinear = (1 + x * n[0]) * (1 + y * n[1]) * (1 + z * n[2]) / 8;
    N.push_back(type == CellType::hex8 ? trilinear
                                       : trilinear * (x * n[0] + y * n[1] + z * n[2] - 2));
  }
  if (type == CellType::hex20)
    for (int i = 8; i < 20; ++i) {
      const Vec3& n = nodes[i];
      double v = 0.25;
      for (int a = 0; a < 3; ++a) v *= n[a] == 0.0 ? 1 - xi[a] * xi[a] : 1 + xi[a] * n[a];
      N.push_back(v);
    }
  return N;
}

}  // namespace rayint
