// Voxel grids: trilinear and Kuhn (6-tet) interpolation, box clipping, and the ray's Kuhn
// segments and trilinear cubics. See voxel_grid.hpp for the formulas and the choice of the
// decomposition; accuracy claims are backed by tests/test_voxel_grid.cpp ([grid]).
#include "rayint/grid/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace rayint {

namespace {

// Polynomials in s as coefficient arrays of fixed capacity (degree <= 3 here).
using Cubic = std::array<double, 4>;

// (a0 + a1 s) * p, p of degree <= 2.
Cubic times_linear(const Cubic& p, double a0, double a1) {
  Cubic r{};
  for (int k = 0; k < 4; ++k) {
    r[k] += a0 * p[k];
    if (k + 1 < 4) r[k + 1] += a1 * p[k];
  }
  return r;
}

struct IndexRay {  // the ray in grid index coordinates x = (p - origin) / spacing
  Vec3 x0;
  Vec3 dx;
};

IndexRay to_index(const VoxelGrid& g, const ViewRay& ray) {
  return {(ray.origin - g.origin()).cwiseQuotient(g.spacing()),
          ray.direction.cwiseQuotient(g.spacing())};
}

// Crossings of the planes g0 + g1 t = k (k integer) strictly inside (t0, t1), appended.
void plane_crossings(double g0, double g1, double t0, double t1, std::vector<double>& out) {
  if (g1 == 0.0) return;  // parallel: the ray lies in or beside every such plane
  const double a = g0 + g1 * t0, b = g0 + g1 * t1;
  const double lo = std::ceil(std::min(a, b)), hi = std::floor(std::max(a, b));
  for (double k = lo; k <= hi; k += 1.0) {
    const double t = (k - g0) / g1;
    if (t > t0 && t < t1) out.push_back(t);
  }
}

// Sorted crossings of the cube faces (kuhn: also of the Kuhn planes x_i - x_j = k) in (t0, t1),
// exact duplicates removed.
std::vector<double> breakpoints(const IndexRay& r, double t0, double t1, bool kuhn) {
  std::vector<double> t;
  for (int i = 0; i < 3; ++i) plane_crossings(r.x0[i], r.dx[i], t0, t1, t);
  if (kuhn)
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        plane_crossings(r.x0[i] - r.x0[j], r.dx[i] - r.dx[j], t0, t1, t);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

// Cube index and local coordinate of an index-space coordinate, clamped to the grid.
std::pair<int, double> cube_and_local(double x, int n) {
  x = std::clamp(x, 0.0, static_cast<double>(n - 1));
  const int c = std::min(static_cast<int>(std::floor(x)), n - 2);
  return {c, x - c};
}

}  // namespace

VoxelGrid::VoxelGrid(std::array<int, 3> dims, Vec3 origin, Vec3 spacing,
                     std::vector<double> values)
    : dims_(dims), origin_(std::move(origin)), spacing_(std::move(spacing)),
      values_(std::move(values)) {
  std::size_t n = 1;
  for (int i = 0; i < 3; ++i) {
    if (dims_[i] < 2) throw std::invalid_argument("VoxelGrid: each dimension needs >= 2 points");
    if (!(std::isfinite(spacing_[i]) && spacing_[i] > 0.0))
      throw std::invalid_argument("VoxelGrid: spacing must be finite and > 0");
    if (!std::isfinite(origin_[i])) throw std::invalid_argument("VoxelGrid: origin not finite");
    n *= static_cast<std::size_t>(dims_[i]);
  }
  if (values_.size() != n)
    throw std::invalid_argument("VoxelGrid: " + std::to_string(values_.size()) +
                                " values for " + std::to_string(n) + " points");
  for (double v : values_)
    if (!std::isfinite(v)) throw std::invalid_argument("VoxelGrid: value not finite");
}

std::string check_direction(const Eigen::Matrix3d& d) {
  if (!d.allFinite()) return "Direction has a value that is not finite";
  const Eigen::Matrix3d e = d.transpose() * d - Eigen::Matrix3d::Identity();
  if (!(e.cwiseAbs().maxCoeff() <= 1e-12))
    return "Direction is not orthonormal (a rotation or reflection; a sheared or scaled Direction is not read)";
  return {};
}

void VoxelGrid::set_placement(const GridPlacement& p) {
  const std::string why = check_direction(p.direction);
  if (!why.empty()) throw std::invalid_argument("VoxelGrid: " + why);
  if (!p.pivot.allFinite()) throw std::invalid_argument("VoxelGrid: placement pivot not finite");
  placement_ = p;
}

void VoxelGrid::set_hidden_cubes(std::vector<unsigned char> hidden) {
  const std::size_t cubes = static_cast<std::size_t>(dims_[0] - 1) * static_cast<std::size_t>(dims_[1] - 1) *
                            static_cast<std::size_t>(dims_[2] - 1);
  if (!hidden.empty() && hidden.size() != cubes)
    throw std::invalid_argument("VoxelGrid: hidden-cube mask of " + std::to_string(hidden.size()) +
                                " entries for " + std::to_string(cubes) + " cubes");
  if (std::none_of(hidden.begin(), hidden.end(), [](unsigned char h) { return h != 0; })) hidden.clear();
  hidden_ = std::move(hidden);
}

std::size_t VoxelGrid::hidden_cube_count() const {
  return static_cast<std::size_t>(
      std::count_if(hidden_.begin(), hidden_.end(), [](unsigned char h) { return h != 0; }));
}

Vec3 VoxelGrid::upper() const {
  return origin_ + Vec3(dims_[0] - 1, dims_[1] - 1, dims_[2] - 1).cwiseProduct(spacing_);
}

double VoxelGrid::sample(const Vec3& p) const {
  const Vec3 x = (p - origin_).cwiseQuotient(spacing_);
  const auto [i, u] = cube_and_local(x[0], dims_[0]);
  const auto [j, v] = cube_and_local(x[1], dims_[1]);
  const auto [k, w] = cube_and_local(x[2], dims_[2]);
  double f = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, d = (c >> 2) & 1;
    f += (a ? u : 1.0 - u) * (b ? v : 1.0 - v) * (d ? w : 1.0 - w) * value(i + a, j + b, k + d);
  }
  return f;
}

double VoxelGrid::kuhn_value(const Vec3& p) const {
  const Vec3 x = (p - origin_).cwiseQuotient(spacing_);
  std::array<int, 3> c{};
  std::array<double, 3> u{};
  for (int i = 0; i < 3; ++i) std::tie(c[i], u[i]) = cube_and_local(x[i], dims_[i]);
  // The Kuhn tet containing u: the axes ordered by decreasing u; its vertices walk from the
  // cube's lower corner along those axes. Barycentric weights 1-u1, u1-u2, u2-u3, u3 (all >= 0).
  std::array<int, 3> axis{0, 1, 2};
  std::sort(axis.begin(), axis.end(), [&](int a, int b) { return u[a] > u[b]; });
  std::array<int, 3> vtx = c;
  double f = (1.0 - u[axis[0]]) * value(vtx[0], vtx[1], vtx[2]);
  for (int m = 0; m < 3; ++m) {
    ++vtx[axis[m]];
    const double weight = m < 2 ? u[axis[m]] - u[axis[m + 1]] : u[axis[2]];
    f += weight * value(vtx[0], vtx[1], vtx[2]);
  }
  return f;
}

Ray ray_segments(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background) {
  return ray_segments(grid, ray, RaySpan{0.0, std::numeric_limits<double>::infinity(), true},
                      background);
}

Ray ray_segments(const VoxelGrid& grid, const ViewRay& ray, const RaySpan& within,
                 const Rgb& background) {
  Ray out;
  out.background = background;
  RaySpan span = grid.clip(ray);
  if (!span.hit || !within.hit) return out;
  span.t_enter = std::max(span.t_enter, within.t_enter);
  span.t_exit = std::min(span.t_exit, within.t_exit);
  if (!(span.t_exit > span.t_enter)) return out;
  const IndexRay r = to_index(grid, ray);
  std::vector<double> t = breakpoints(r, span.t_enter, span.t_exit, true);
  t.insert(t.begin(), span.t_enter);
  t.push_back(span.t_exit);
  const double speed = ray.direction.norm();
  std::vector<double> f(t.size());
  for (std::size_t m = 0; m < t.size(); ++m) f[m] = grid.kuhn_value(ray.origin + t[m] * ray.direction);
  out.segments.reserve(t.size() - 1);
  const auto& dims = grid.dims();
  for (std::size_t m = t.size() - 1; m-- > 0;) {  // far -> near
    if (grid.has_hidden_cubes()) {
      const double t_mid = 0.5 * (t[m] + t[m + 1]);
      std::array<int, 3> c{};
      for (int i = 0; i < 3; ++i) c[i] = cube_and_local(r.x0[i] + t_mid * r.dx[i], dims[i]).first;
      if (grid.cube_hidden(c[0], c[1], c[2])) continue;  // empty: passes the light unchanged
    }
    out.segments.push_back({(t[m + 1] - t[m]) * speed, f[m + 1], f[m]});
  }
  return out;
}

namespace {

// The trilinear weight of each corner c of `cube` (bit i of c: upper side on axis i) along the
// ray as a cubic in s, the distance from the piece's far end (t = t_far - s / speed): the
// product over the axes of u_i(s) = a_i + b_i s or 1 - u_i(s).
std::array<Cubic, 8> corner_cubics(const IndexRay& r, const std::array<int, 3>& cube, double t_far, double speed) {
  std::array<double, 3> a{}, b{};
  for (int i = 0; i < 3; ++i) {
    a[i] = r.x0[i] + t_far * r.dx[i] - cube[i];
    b[i] = -r.dx[i] / speed;
  }
  std::array<Cubic, 8> out{};
  for (int c = 0; c < 8; ++c) {
    Cubic p{1.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < 3; ++i) {
      const bool upper_side = (c >> i) & 1;
      p = upper_side ? times_linear(p, a[i], b[i]) : times_linear(p, 1.0 - a[i], -b[i]);
    }
    out[static_cast<std::size_t>(c)] = p;
  }
  return out;
}

}  // namespace

std::array<std::array<double, 4>, 8> trilinear_corner_cubics(const VoxelGrid& grid, const ViewRay& ray,
                                                             const TrilinearCubic& piece) {
  return corner_cubics(to_index(grid, ray), piece.cube, piece.t_far, ray.direction.norm());
}

std::size_t trilinear_corner_index(const VoxelGrid& grid, const std::array<int, 3>& cube, int corner) {
  const auto& d = grid.dims();
  return static_cast<std::size_t>(cube[0] + (corner & 1)) +
         static_cast<std::size_t>(d[0]) * (static_cast<std::size_t>(cube[1] + ((corner >> 1) & 1)) +
                                           static_cast<std::size_t>(d[1]) *
                                               static_cast<std::size_t>(cube[2] + ((corner >> 2) & 1)));
}

void trilinear_cubics(const VoxelGrid& grid, const ViewRay& ray, std::vector<TrilinearCubic>& out,
                      std::vector<double>& t) {
  out.clear();
  t.clear();
  const RaySpan span = grid.clip(ray);
  if (!span.hit || !(span.t_exit > span.t_enter)) return;
  const IndexRay r = to_index(grid, ray);
  // Per axis the crossings come out in increasing t when dx > 0, decreasing when dx < 0:
  // reverse those, then merge the three sorted runs (the DDA order) and drop bit-equal repeats.
  t.push_back(span.t_enter);
  std::size_t run_begin[4] = {1, 0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    plane_crossings(r.x0[i], r.dx[i], span.t_enter, span.t_exit, t);
    if (r.dx[i] < 0.0) std::reverse(t.begin() + static_cast<std::ptrdiff_t>(run_begin[i]), t.end());
    run_begin[i + 1] = t.size();
  }
  std::inplace_merge(t.begin() + 1, t.begin() + static_cast<std::ptrdiff_t>(run_begin[1]),
                     t.begin() + static_cast<std::ptrdiff_t>(run_begin[2]));
  std::inplace_merge(t.begin() + 1, t.begin() + static_cast<std::ptrdiff_t>(run_begin[2]), t.end());
  t.push_back(span.t_exit);
  t.erase(std::unique(t.begin(), t.end()), t.end());
  const double speed = ray.direction.norm();
  const auto& dims = grid.dims();
  out.reserve(t.size() - 1);
  for (std::size_t m = t.size() - 1; m-- > 0;) {
    TrilinearCubic piece;
    piece.t_far = t[m + 1];
    piece.t_near = t[m];
    const double t_mid = 0.5 * (piece.t_far + piece.t_near);
    for (int i = 0; i < 3; ++i) piece.cube[i] = cube_and_local(r.x0[i] + t_mid * r.dx[i], dims[i]).first;
    if (grid.cube_hidden(piece.cube[0], piece.cube[1], piece.cube[2])) continue;  // empty (blanked)
    const std::array<Cubic, 8> basis = corner_cubics(r, piece.cube, piece.t_far, speed);
    Cubic f{};
    for (int c = 0; c < 8; ++c) {
      const double fv = grid.value(piece.cube[0] + (c & 1), piece.cube[1] + ((c >> 1) & 1),
                                   piece.cube[2] + ((c >> 2) & 1));
      for (int k = 0; k < 4; ++k) f[k] += fv * basis[static_cast<std::size_t>(c)][k];
    }
    piece.length = (piece.t_far - piece.t_near) * speed;
    piece.coeffs = f;
    out.push_back(piece);
  }
}

std::vector<TrilinearPiece> trilinear_pieces(const VoxelGrid& grid, const ViewRay& ray) {
  std::vector<TrilinearCubic> cubics;
  std::vector<double> scratch;
  trilinear_cubics(grid, ray, cubics, scratch);
  std::vector<TrilinearPiece> out;
  out.reserve(cubics.size());
  for (const TrilinearCubic& c : cubics) {
    TrilinearPiece piece;
    piece.cube = c.cube;
    piece.t_far = c.t_far;
    piece.t_near = c.t_near;
    piece.segment.length = c.length;
    piece.segment.coeffs.assign(c.coeffs.begin(), c.coeffs.end());
    out.push_back(std::move(piece));
  }
  return out;
}

PolyRay trilinear_ray(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background) {
  PolyRay out;
  out.background = background;
  for (auto& piece : trilinear_pieces(grid, ray)) out.segments.push_back(std::move(piece.segment));
  return out;
}

}  // namespace rayint
