// The ray/box clip; see bounds.hpp.
#include "rayint/geometry/bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rayint {

bool Bounds::contains(const Vec3& p) const {
  for (int a = 0; a < 3; ++a)
    if (!(p[a] >= lower[a] && p[a] <= upper[a])) return false;
  return true;
}

bool Bounds::finite() const { return lower.allFinite() && upper.allFinite(); }

Bounds point_bounds(const std::vector<Vec3>& points) {
  if (points.empty()) return {Vec3::Zero(), Vec3::Zero()};
  Bounds b{points.front(), points.front()};
  for (const Vec3& p : points) {
    b.lower = b.lower.cwiseMin(p);
    b.upper = b.upper.cwiseMax(p);
  }
  return b;
}

RaySpan Bounds::clip(const ViewRay& ray) const {
  double t_enter = 0.0;
  double t_exit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a];
    const double d = ray.direction[a];
    if (d == 0.0) {
      if (!(o >= lower[a] && o <= upper[a])) return {};
      continue;
    }
    double ta = (lower[a] - o) / d;
    double tb = (upper[a] - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t_enter = std::max(t_enter, ta);  // keeps t_enter when ta is NaN (never: lower/upper finite or inf)
    t_exit = std::min(t_exit, tb);
  }
  if (!(t_exit > t_enter) || !std::isfinite(t_exit)) return {};
  return {t_enter, t_exit, true};
}

SlabInterval padded_slab_interval(const Vec3& lower, const Vec3& upper, double pad, const Vec3& origin,
                                  const Vec3& d) {
  SlabInterval s{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (int k = 0; k < 3; ++k) {
    const double lo = lower[k] - pad, hi = upper[k] + pad;
    if (d[k] == 0.0) {
      if (origin[k] < lo || origin[k] > hi) s.t1 = -1.0;
    } else {
      double a = (lo - origin[k]) / d[k], b = (hi - origin[k]) / d[k];
      if (a > b) std::swap(a, b);
      s.t0 = std::max(s.t0, a);
      s.t1 = std::min(s.t1, b);
    }
  }
  return s;
}

MeshWalkStart mesh_walk_start(const ViewRay& ray, const Vec3& lower, const Vec3& upper, double diagonal) {
  MeshWalkStart w;
  Vec3 d = ray.direction;
  const double dnorm = d.norm();
  if (dnorm > 0.0 && std::isfinite(dnorm)) d /= dnorm;
  w.direction = d;
  w.origin = ray.origin;
  const SlabInterval box = padded_slab_interval(lower, upper, 1e-6 * diagonal + 1e-300, ray.origin, d);
  w.empty = !(box.t1 >= std::max(box.t0, 0.0)) || !(dnorm > 0.0);
  if (w.empty) return w;
  const double t_base = box.t0 - 0.01 * diagonal;
  w.origin = ray.origin + t_base * d;
  w.t_eye = -t_base;
  w.t_end = box.t1 - t_base + 0.01 * diagonal;
  return w;
}

}  // namespace rayint
