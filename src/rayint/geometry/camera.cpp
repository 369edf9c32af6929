#include "rayint/geometry/camera.hpp"

#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"

namespace rayint {

void Camera::validate() const {
  if (width < 1 || height < 1) throw std::invalid_argument("width and height must be >= 1");
  if (width > 16384 || height > 16384)
    throw std::invalid_argument("width and height must be <= 16384");
  const Vec3 forward = look_at - position;
  if (!(forward.norm() > 0.0) || !forward.allFinite())
    throw std::invalid_argument("look_at must differ from position");
  if (!up.allFinite() || !(forward.normalized().cross(up).norm() > 1e-12))
    throw std::invalid_argument("up must not be parallel to the view direction");
  if (projection == Projection::perspective && !(fov_deg > 0.0 && fov_deg < 180.0))
    throw std::invalid_argument("fov_deg must be in (0, 180)");
  if (projection == Projection::orthographic && !(ortho_height > 0.0 && std::isfinite(ortho_height)))
    throw std::invalid_argument("ortho_height must be > 0");
}

ViewRay Camera::ray_for_pixel(int x, int y) const { return ray_at(x + 0.5, y + 0.5); }

ViewRay Camera::ray_at(double px, double py) const {
  const Vec3 forward = (look_at - position).normalized();
  const Vec3 right = forward.cross(up).normalized();
  const Vec3 true_up = right.cross(forward);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  // Normalized device coordinates in [-1, 1], y up.
  const double u = (2.0 * px / width - 1.0) * aspect;
  const double v = 1.0 - 2.0 * py / height;
  ViewRay ray;
  if (projection == Projection::perspective) {
    const double half = std::tan(0.5 * fov_deg * kPi / 180.0);
    ray.origin = position;
    ray.direction = (forward + u * half * right + v * half * true_up).normalized();
  } else {
    const double half = 0.5 * ortho_height;
    ray.origin = position + u * half * right + v * half * true_up;
    ray.direction = forward;
  }
  return ray;
}

}  // namespace rayint
