#include "rayint/geometry/camera_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"

namespace rayint {

Camera fit_camera(const Camera& camera, const Vec3& lo, const Vec3& hi, double margin) {
  camera.validate();
  if (!lo.allFinite() || !hi.allFinite() || (hi - lo).minCoeff() < 0.0)
    throw std::invalid_argument("fit_camera: the box is empty or not finite");
  const Vec3 centre = 0.5 * (lo + hi);
  // A flat or point-like box still gets a view of positive size.
  const double radius = margin * std::max(0.5 * (hi - lo).norm(), 1e-12 * std::max(1.0, centre.norm()));
  const Vec3 forward = (camera.look_at - camera.position).normalized();
  const double aspect = static_cast<double>(camera.width) / static_cast<double>(camera.height);
  Camera fitted = camera;
  fitted.look_at = centre;
  if (camera.projection == Camera::Projection::perspective) {
    const double half_v = 0.5 * camera.fov_deg * kPi / 180.0;
    const double half_h = std::atan(std::tan(half_v) * aspect);
    const double half = std::min(half_v, half_h);
    fitted.position = centre - forward * (radius / std::sin(half));
  } else {
    fitted.ortho_height = 2.0 * radius * std::max(1.0, 1.0 / aspect);
    fitted.position = centre - forward * (2.0 * radius);
  }
  fitted.validate();
  return fitted;
}

}  // namespace rayint
