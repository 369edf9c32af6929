// The image-loss gradient of a voxel-grid scene; what is differentiated and the failure rule are
// in grid_loss_gradient.hpp.
#include "rayint/scene/grid_loss_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/scene/grid_gradient.hpp"

namespace rayint {

std::string grid_gradient_refusal(const Scene& scene, const ScenePipeline& pipeline) {
  if (dynamic_cast<const GridField*>(&scene.medium.field()) == nullptr)
    return "medium.type: --grad-out differentiates a voxel grid (\"grid\"), not " + scene.medium.field().kind();
  if (!scene.has("absorption"))
    return "effects: --grad-out differentiates the emission-absorption image (\"absorption\", optionally "
           "with \"emission\"); \"absorption\" is not named";
  for (const std::string& e : scene.effects)
    if (e != "absorption" && e != "emission")
      return "effects: --grad-out differentiates \"absorption\" and \"emission\" only, not \"" + e + "\"";
  for (const auto& effect : pipeline.effects())
    if (effect->method_label() != "exact")
      return "methods." + effect->name() + ": --grad-out differentiates the exact method, not " +
             effect->method_label();
  return "";
}

GridLossGradient grid_image_loss_gradient(const ScenePipeline& pipeline, const Image& target, unsigned threads) {
  const Scene& scene = pipeline.scene();
  const std::string refusal = grid_gradient_refusal(scene, pipeline);
  if (!refusal.empty()) throw std::invalid_argument(refusal);
  const auto& field = dynamic_cast<const GridField&>(scene.medium.field());
  const VoxelGrid& grid = field.grid();
  const int width = scene.camera ? scene.camera->width : static_cast<int>(scene.rays.size());
  const int height = scene.camera ? scene.camera->height : 1;
  if (target.width != width || target.height != height)
    throw std::invalid_argument("target image is " + std::to_string(target.width) + " x " +
                                std::to_string(target.height) + ", the scene renders " + std::to_string(width) +
                                " x " + std::to_string(height));
  // The render's transfer functions: extinction as density, emission as colour (0 without it).
  const TransferFunctions tf = scene.medium.transfer().emission_absorption(scene.has("emission"));
  const bool trilinear = field.interpolation() == GridInterpolation::trilinear;
  std::unique_ptr<TrilinearIntegrator> integrator;
  if (trilinear) integrator = std::make_unique<TrilinearIntegrator>(tf);
  const ExactRayGradient gradient(tf);  // Kuhn path: the functions prepared once for every pixel

  GridLossGradient out;
  out.interpolation = field.interpolation();
  out.dims = grid.dims();
  out.image = Image(width, height);
  const std::size_t n = grid.point_count();
  const unsigned workers = parallel_workers(height, threads);
  struct Part {
    std::vector<double> d_value;
    double loss = 0.0;
    long failed = 0;
    long long first_failed = -1;  // pixel index
    std::string why;
  };
  std::vector<Part> parts(workers);
  for (Part& p : parts) p.d_value.assign(n, 0.0);
  parallel_for_striped(height, threads, [&](long long row, unsigned id) {
    Part& p = parts[id];
    std::vector<std::size_t> index;
    std::vector<Rgb> d_value;
    for (int x = 0; x < width; ++x) {
      const long long pixel = row * width + x;
      const PixelRay pr = pipeline.ray(pixel);
      const ViewRay view = field.to_grid(pr.ray);
      Rgb intensity{};
      std::string undefined;
      if (trilinear) {
        TrilinearGradient g = integrator->gradient(grid, view, pr.background);
        intensity = g.intensity;
        index = std::move(g.index);
        d_value = std::move(g.d_value);
        undefined = std::move(g.undefined);
      } else {
        GridPixelJacobian g = grid_pixel_jacobian(grid, gradient, view, pr.background);
        intensity = g.intensity;
        index = std::move(g.index);
        d_value = std::move(g.d_value);
        undefined = std::move(g.undefined);
      }
      const int y = static_cast<int>(row);
      out.image.at(x, y) = intensity;
      Rgb weight{};
      bool finite = true;
      for (int c = 0; c < kChannels; ++c) {
        const double r = intensity[c] - target.at(x, y)[c];
        weight[c] = 2.0 * r;
        p.loss += r * r;
        finite = finite && std::isfinite(r);
      }
      for (const Rgb& d : d_value)
        for (int c = 0; c < kChannels; ++c) finite = finite && std::isfinite(d[c]);
      if (!finite || !undefined.empty()) {  // undefined: a derivative does not exist (a jump)
        if (p.failed++ == 0 || pixel < p.first_failed) {
          p.first_failed = pixel;
          p.why = !undefined.empty() ? undefined : "non-finite intensity or derivative";
        }
        continue;
      }
      for (std::size_t i = 0; i < index.size(); ++i) {
        double s = 0.0;
        for (int c = 0; c < kChannels; ++c) s += weight[c] * d_value[i][c];
        p.d_value[index[i]] += s;
      }
    }
  });
  out.d_value.assign(n, 0.0);
  long long first = -1;
  // Summed in worker order; each worker took fixed rows (parallel_for_striped): the same sums,
  // bit for bit, on every run with the same thread count.
  for (const Part& p : parts) {
    for (std::size_t i = 0; i < n; ++i) out.d_value[i] += p.d_value[i];
    out.loss += p.loss;
    out.pixels_failed += p.failed;
    if (p.failed > 0 && (first < 0 || p.first_failed < first)) {
      first = p.first_failed;
      out.first_failure = "pixel (" + std::to_string(first % width) + ", " + std::to_string(first / width) +
                          "): " + p.why;
    }
  }
  return out;
}

}  // namespace rayint
