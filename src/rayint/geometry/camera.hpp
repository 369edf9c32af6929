#pragma once
// A pinhole or orthographic camera that generates one viewing ray per pixel, shared by mesh
// cases (`rayint render CASE.json`) and scenes.
//
// Conventions: the image plane is spanned by `right` = normalize(forward x up) and
// `true_up` = right x forward; pixel (x, y) has its centre at ((x + 0.5)/width, (y + 0.5)/height)
// in normalized coordinates, row y = 0 at the top of the image. Perspective: `fov_deg` is the
// full vertical field of view. Orthographic: `ortho_height` is the full vertical extent of the
// view in world units; every ray starts on the plane through `position` perpendicular to
// `forward` and points along `forward`.
#include "rayint/geometry/vec3.hpp"

namespace rayint {

struct Camera {
  enum class Projection { perspective, orthographic };

  Vec3 position = Vec3(0.0, 0.0, 5.0);
  Vec3 look_at = Vec3::Zero();
  Vec3 up = Vec3::UnitY();
  Projection projection = Projection::perspective;
  double fov_deg = 40.0;       // perspective: full vertical field of view, degrees, in (0, 180)
  double ortho_height = 2.0;   // orthographic: full vertical extent, world units, > 0
  int width = 64;
  int height = 64;

  // Throws std::invalid_argument when the frame is degenerate (look_at == position, up parallel
  // to the view direction) or a size or angle is out of range.
  void validate() const;

  // The ray through the centre of pixel (x, y); x in [0, width), y in [0, height).
  ViewRay ray_for_pixel(int x, int y) const;
  // The same for a sub-pixel position (px, py) in pixel units (pixel centre = x + 0.5).
  ViewRay ray_at(double px, double py) const;
};

// A camera's frame (forward, right, true_up, the half extent), formed once: the rays of
// Camera::ray_for_pixel / ray_at, bit for bit (those call this), without two normalisations, a
// cross product and a tangent per ray (~2% of a 512 x 512 mesh render; issue 33, round 12).
class CameraRays {
 public:
  explicit CameraRays(const Camera& camera);
  ViewRay ray_for_pixel(int x, int y) const { return ray_at(x + 0.5, y + 0.5); }
  ViewRay ray_at(double px, double py) const;

 private:
  Vec3 position_, forward_, right_, true_up_;
  double aspect_ = 1.0, half_ = 1.0, width_ = 1.0, height_ = 1.0;
  bool perspective_ = true;
};

}  // namespace rayint
