// Undistorted higher-order cells: geometry, the polynomial along a ray, and the decomposition
// into linear tetrahedra (see cell.hpp).
#include "rayint/cells/cell.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace rayint {

namespace {

void check_cell(const HigherOrderCell& c) {
  if (static_cast<int>(c.values.size()) != node_count(c.type))
    throw std::invalid_argument(std::string("cell: ") + cell_type_name(c.type) + " needs " +
                                std::to_string(node_count(c.type)) + " node values");
  for (double v : c.values)
    if (!std::isfinite(v)) throw std::invalid_argument("cell: node values must be finite");
  if (!c.origin.allFinite() || !c.axes.allFinite())
    throw std::invalid_argument("cell: coordinates must be finite");
  const double scale = c.axes.col(0).norm() * c.axes.col(1).norm() * c.axes.col(2).norm();
  if (!(std::abs(c.axes.determinant()) > 1e-12 * scale))
    throw std::invalid_argument("cell: degenerate geometry");
}

using Poly = std::vector<double>;

Poly multiply(const Poly& p, double a0, double a1) {  // p * (a0 + a1 s)
  Poly r(p.size() + 1, 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    r[k] += a0 * p[k];
    r[k + 1] += a1 * p[k];
  }
  return r;
}

// The Kuhn-coordinate map of a cell: K = kuhn_matrix * xi + kuhn_offset, and the grid over it.
Eigen::Matrix3d kuhn_matrix(CellType type) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  if (type == CellType::tet10) M << 1, 1, 1, 0, 1, 1, 0, 0, 1;  // (a, b, c)
  return M;
}

}  // namespace

HigherOrderCell make_tet10(const std::array<Vec3, 4>& corners, std::vector<double> values) {
  HigherOrderCell c;
  c.type = CellType::tet10;
  c.origin = corners[0];
  for (int i = 0; i < 3; ++i) c.axes.col(i) = corners[i + 1] - corners[0];
  c.values = std::move(values);
  check_cell(c);
  return c;
}

HigherOrderCell make_brick(CellType type, const Vec3& centre, const Eigen::Matrix3d& half_axes,
                           std::vector<double> values) {
  if (!is_brick(type)) throw std::invalid_argument("make_brick: hex8 or hex20");
  HigherOrderCell c;
  c.type = type;
  c.origin = centre;
  c.axes = half_axes;
  c.values = std::move(values);
  check_cell(c);
  return c;
}

Vec3 to_reference(const HigherOrderCell& cell, const Vec3& world) {
  return cell.axes.partialPivLu().solve(world - cell.origin);
}

Vec3 to_world(const HigherOrderCell& cell, const Vec3& xi) { return cell.origin + cell.axes * xi; }

double cell_value(const HigherOrderCell& cell, const Vec3& world) {
  const std::vector<double> N = shape_functions(cell.type, to_reference(cell, world));
  double f = 0.0;
  for (std::size_t i = 0; i < N.size(); ++i) f += N[i] * cell.values[i];
  return f;
}

CellChord cell_chord(const HigherOrderCell& cell, const ViewRay& ray) {
  check_cell(cell);
  const auto lu = cell.axes.partialPivLu();
  const Vec3 r0 = lu.solve(ray.origin - cell.origin), r1 = lu.solve(ray.direction);
  // Constraints a + b t >= 0 of the closed cell.
  std::vector<std::pair<double, double>> halfspaces;
  if (cell.type == CellType::tet10) {
    halfspaces.emplace_back(1.0 - r0.sum(), -r1.sum());
    for (int i = 0; i < 3; ++i) halfspaces.emplace_back(r0[i], r1[i]);
  } else {
    for (int i = 0; i < 3; ++i) {
      halfspaces.emplace_back(1.0 + r0[i], r1[i]);
      halfspaces.emplace_back(1.0 - r0[i], -r1[i]);
    }
  }
  double t_enter = 0.0, t_exit = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : halfspaces) {
    if (b == 0.0) {
      if (a < 0.0) return {};
      continue;
    }
    const double t = -a / b;
    if (b > 0.0) t_enter = std::max(t_enter, t);
    else t_exit = std::min(t_exit, t);
  }
  CellChord chord;
  if (!(t_exit > t_enter) || !std::isfinite(t_exit)) return chord;
  chord.span = {t_enter, t_exit, true};
  const double speed = ray.direction.norm();
  chord.segment.length = (t_exit - t_enter) * speed;
  // xi(s) = xi_far + s * v: s runs from the far end (t_exit) toward the eye.
  const Vec3 xi_far = r0 + t_exit * r1, v = -r1 / speed;
  Poly f(static_cast<std::size_t>(ray_degree(cell.type)) + 1, 0.0);
  const std::vector<ShapeProduct>& products = shape_products(cell.type);
  for (std::size_t i = 0; i < products.size(); ++i) {
    Poly p{products[i].scale * cell.values[i]};
    for (const LinearFactor& L : products[i].factors)
      p = multiply(p, L.c0 + L.c1.dot(xi_far), L.c1.dot(v));
    for (std::size_t k = 0; k < p.size(); ++k) f[k] += p[k];
  }
  chord.segment.coeffs = std::move(f);
  return chord;
}

PolyRay cell_poly_ray(const HigherOrderCell& cell, const ViewRay& ray, const Rgb& background) {
  PolyRay out;
  out.background = background;
  const CellChord chord = cell_chord(cell, ray);
  if (chord.span.hit) out.segments.push_back(chord.segment);
  return out;
}

Ray decomposed_ray(const HigherOrderCell& cell, const ViewRay& ray, int level,
                   const Rgb& background) {
  if (level < 1) throw std::invalid_argument("decomposed_ray: level must be >= 1");
  const CellChord chord = cell_chord(cell, ray);
  Ray out;
  out.background = background;
  if (!chord.span.hit) return out;
  // The Kuhn grid in K coordinates: bricks K = xi on [-1, 1]^3, tets K = (a, b, c) on [0, 1]^3.
  const bool brick = is_brick(cell.type);
  const Eigen::Matrix3d M = kuhn_matrix(cell.type), M_inv = M.inverse();
  const double lo = brick ? -1.0 : 0.0, h = (brick ? 2.0 : 1.0) / level;
  const int n = level + 1;
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 K(lo + i * h, lo + j * h, lo + k * h);
        const std::vector<double> N = shape_functions(cell.type, M_inv * K);
        double f = 0.0;
        for (std::size_t m = 0; m < N.size(); ++m) f += N[m] * cell.values[m];
        values.push_back(f);
      }
  const VoxelGrid grid({n, n, n}, Vec3::Constant(lo), Vec3::Constant(h), std::move(values));
  const auto lu = cell.axes.partialPivLu();
  const ViewRay k_ray{M * lu.solve(ray.origin - cell.origin), M * lu.solve(ray.direction)};
  out = ray_segments(grid, k_ray, chord.span, background);
  const double scale = ray.direction.norm() / k_ray.direction.norm();  // K lengths -> world
  for (Segment& s : out.segments) s.length *= scale;
  return out;
}

}  // namespace rayint
