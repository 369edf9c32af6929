#pragma once
// Framing a box with a camera (`rayint render --fit`): keep the camera's view direction, up,
// projection, field of view and image size, and move it so that the sphere around the box
// (centre = box centre, radius = half the box diagonal) fills the view with a margin. The sphere
// is used, not the box's projected corners, so the framing does not depend on the direction and
// the whole box is always inside the image.
#include "rayint/geometry/camera.hpp"

namespace rayint {

// `lo`, `hi`: the box's corners (lo <= hi componentwise, finite). `margin` >= 1: the sphere's
// radius is taken `margin` times larger. Perspective: the camera stands at the distance where the
// sphere touches the narrower of the vertical and horizontal fields of view. Orthographic:
// `ortho_height` is set so that the sphere fits both ways, and the camera stands 2 radii back.
// Throws std::invalid_argument for a non-finite box or a degenerate camera (Camera::validate).
Camera fit_camera(const Camera& camera, const Vec3& lo, const Vec3& hi, double margin = 1.05);

}  // namespace rayint
