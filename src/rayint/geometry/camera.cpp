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

ViewRay Camera::ray_at(double px, double py) const { return CameraRays(*this).ray_at(px, py); }

CameraRays::CameraRays(const Camera& camera)
    : position_(camera.position),
      forward_((camera.look_at - camera.position).normalized()),
      right_(forward_.cross(camera.up).normalized()),
      true_up_(right_.cross(forward_)),
      aspect_(static_cast<double>(camera.width) / static_cast<double>(camera.height)),
      half_(camera.projection == Camera::Projection::perspective ? std::tan(0.5 * camera.fov_deg * kPi / 180.0)
                                                                 : 0.5 * camera.ortho_height),
      width_(camera.width),
      height_(camera.height),
      perspective_(camera.projection == Camera::Projection::perspective) {}

ViewRay CameraRays::ray_at(double px, double py) const {
  // Normalized device coordinates in [-1, 1], y up.
  const double u = (2.0 * px / width_ - 1.0) * aspect_;
  const double v = 1.0 - 2.0 * py / height_;
  ViewRay ray;
  if (perspective_) {
    ray.origin = position_;
    ray.direction = (forward_ + u * half_ * right_ + v * half_ * true_up_).normalized();
  } else {
    ray.origin = position_ + u * half_ * right_ + v * half_ * true_up_;
    ray.direction = forward_;
  }
  return ray;
}

}  // namespace rayint
