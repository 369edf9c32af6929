#pragma once
// The gradient of an image loss of a voxel-grid scene with respect to every grid point value
// (issue 28, images; `rayint render SCENE --loss-target T --grad-out G`, cli/render_scene_gradient.cpp).
//
// What is differentiated: the scene's emission-absorption image (effects "absorption", or
// "absorption" and "emission", method exact: pixel = B T + E, docs/scenes.md) of a medium of type
// "grid", in the grid's own interpolation (scene/grid_field.hpp):
//  * trilinear (the default): TrilinearIntegrator::gradient (grid/trilinear_integral.hpp), the
//    derivative of the exact trilinear integral the scene renders with;
//  * kuhn ("interpolation": "kuhn"): grid_pixel_jacobian (scene/grid_gradient.hpp), the chain rule
//    through the Kuhn segments the scene renders.
// Each pixel's ray is the pipeline's (ScenePipeline::ray: the camera's pixel or an explicit ray,
// with its background colour or background-image texel), taken to the grid's own frame
// (GridField::to_grid: a rotated image's Direction moves rays, not point values). The pixel is
// the gradient's forward intensity with the background entering at the far end: the render's
// B T + E composited in one pass (equal to `rayint render`'s image to rounding, ~1e-16 relative:
// tests/test_grid_grad_cli.cpp checks 1e-13).
// loss = sum over pixels and channels of (I - target)^2; dloss/dv = sum 2 (I - target) dI/dv.
// A pixel whose intensity or grid-value derivative is not finite, or whose gradient says a
// derivative does not exist (`undefined`: both interpolations leave NaN where a ray touches a
// transfer-function jump), is counted in pixels_failed with the reason and adds nothing; callers
// show the run as failed.
#include <array>
#include <string>
#include <vector>

#include "rayint/render/image.hpp"
#include "rayint/scene/grid_field.hpp"
#include "rayint/scene/pipeline.hpp"

namespace rayint {

struct GridLossGradient {
  Image image;  // the pixels differentiated (width x height; explicit rays: N x 1)
  double loss = 0.0;
  GridInterpolation interpolation = GridInterpolation::trilinear;
  std::array<int, 3> dims{};   // the grid's points per axis (nx, ny, nz)
  std::vector<double> d_value;  // dloss / d value, in VoxelGrid::values() order: i + nx (j + ny k)
  long pixels_failed = 0;
  std::string first_failure;   // empty, or the first failed pixel and why
};

// Empty when `scene` is what grid_image_loss_gradient differentiates; else "FIELD: what" naming
// the scene field that is not (for a reader's one-line message): medium.type, effects, methods.
std::string grid_gradient_refusal(const Scene& scene, const ScenePipeline& pipeline);

// Throws std::invalid_argument with grid_gradient_refusal's text, or when `target` is not the
// image's size.
GridLossGradient grid_image_loss_gradient(const ScenePipeline& pipeline, const Image& target, unsigned threads = 0);

}  // namespace rayint
