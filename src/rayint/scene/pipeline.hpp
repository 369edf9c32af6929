#pragma once
// The scene pipeline: the named effects, assembled from the registry (scene/effect.hpp), evaluated
// on every viewing ray (pixel or explicit ray), in parallel, with per-effect time and work; and,
// on request, each term's error against its reference on a subset of the rays.
//
// A pixel is the sum of the named terms, plus the background itself when `absorption` is not
// named (nothing attenuates it then). Terms nobody named are never evaluated: no effect object
// exists for them, and NoShadows casts no shadow ray.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/scene/effect.hpp"
#include "rayint/scene/shadowing.hpp"

namespace rayint {

struct TermError {
  long long rays = 0;            // rays compared
  double max_abs = 0.0;          // over rays and channels
  double mean_abs = 0.0;
  double peak_reference = 0.0;   // largest |reference| over rays and channels
  double max_rel_to_peak = 0.0;  // max_abs / peak_reference
  double max_reference_error = 0.0;  // the reference's own largest error estimate
  bool reference_converged = true;
  double reference_seconds = 0.0;   // summed over threads
};

struct EffectReport {
  std::string effect;
  std::string method;
  std::string role;  // term, attenuation_term, modifier
  EffectWork work;
  Rgb mean_term{};  // the term averaged over every ray (pixel) rendered; zeros for modifiers
  bool has_error = false;
  TermError error;
};

struct SceneRenderOptions {
  unsigned threads = 0;  // 0: all cores
  // Reference errors on error_grid x error_grid pixels spread over the image (0: none). With
  // explicit rays, every ray is compared when error_grid > 0.
  int error_grid = 0;
  std::function<void(double fraction)> progress;  // called from worker threads, serialised
  // The error_grid phase (references are slow): sampled rays done / sampled rays, likewise.
  std::function<void(double fraction)> error_progress;
};

struct SceneRenderResult {
  Image image;                     // width x height (explicit rays: N x 1)
  Rgb image_mean{};                // the pixel (sum of terms) averaged over every ray
  std::vector<EffectReport> effects;
  double render_seconds = 0.0;     // wall time of the pass over the rays (without setup, errors)
  double render_cpu_seconds = 0.0; // process CPU time of the same pass (all threads)
  double setup_cpu_seconds = 0.0;
  double setup_seconds = 0.0;      // wall time of building the pipeline (light grids)
  double error_seconds = 0.0;      // wall time of the reference comparison
  unsigned threads = 1;
  bool has_total_error = false;
  TermError total_error;           // of the whole pixel (sum of terms) against the references' sum
  // Explicit rays only: terms per ray, in the order of `effects` (modifiers give zeros).
  std::vector<std::vector<Rgb>> ray_terms;
};

// One shard's part of a render (`rayint render SCENE --shard I/N`): the lines [line_begin,
// line_end) of `lines`, a line being an image row (camera) or one explicit ray; what the
// assembly needs to give the whole run's figures exactly: the pixels (and explicit rays'
// terms), each line's sums of every term and of the pixel (the means are summed line by line in
// order, so they do not depend on how the lines were split), and the work per term effect (then
// shadows), with the effects' setup. Times are the part's; assembled, they are summed.
struct SceneRenderPart {
  int width = 0, height = 0;  // the whole image (explicit rays: N x 1)
  long long lines = 0, line_begin = 0, line_end = 0;
  std::vector<Rgb> pixels;                    // (line_end - line_begin) lines, in pixel order
  std::vector<std::vector<Rgb>> ray_terms;    // explicit rays: the terms of each ray of the part
  std::vector<std::vector<Rgb>> line_sums;    // per line: each term's sum, then the pixel's
  std::vector<EffectWork> work;               // per term effect, then shadows
  double render_seconds = 0.0, render_cpu_seconds = 0.0, setup_seconds = 0.0, setup_cpu_seconds = 0.0;
  unsigned threads = 1;
};

// The scene's reference image (`rayint check SCENE --candidate-image`): every pixel (or explicit
// ray) is what the pipeline would give if each named term were computed by its effect's
// independent reference (Effect::reference: adaptive Gauss-Kronrod to the scene's
// "reference" tolerances for the deterministic terms, 1,024-sample path tracing for
// multiple_scattering), summed as render sums the terms, plus the unattenuated background when
// `absorption` is not named. `error` is the sum over the terms of each reference's own error
// estimate (absolute, per channel; for Monte Carlo terms two standard errors). Deterministic:
// each pixel is computed on its own, so the image does not depend on the thread count.
struct ReferenceImage {
  Image value;
  Image error;
  long long evaluations = 0;      // integrand evaluations or path samples, over all pixels
  long long unconverged = 0;      // pixels where a reference reported non-convergence
  double max_error = 0.0;         // largest entry of `error`
  double seconds = 0.0;           // wall time
};

class ScenePipeline {
 public:
  // Throws std::invalid_argument for an effect or method that cannot run on this scene.
  ScenePipeline(const Scene& scene, unsigned threads = 0);

  const Scene& scene() const { return scene_; }
  long long ray_count() const;
  PixelRay ray(long long index) const;  // pixel index y * width + x, or explicit ray index
  // The term effects in pipeline order (the registry's), excluding modifiers.
  const std::vector<std::unique_ptr<Effect>>& effects() const { return effects_; }
  const Shadowing& shadowing() const { return *shadowing_; }

  // The whole render: assemble({render_part(options, whole)}), then the errors (error_grid).
  SceneRenderResult render(const SceneRenderOptions& options) const;
  // The lines shard_range gives `shard` (options.error_grid is not used: errors need the whole run).
  SceneRenderPart render_part(const SceneRenderOptions& options, const ShardSpec& shard) const;
  // The render from parts (all of them: the whole run's image, means and work exactly, times
  // summed; some: a partial merge, the missing lines black and left out of the means). Throws
  // std::invalid_argument for a part that does not fit this scene or a line in two parts.
  SceneRenderResult assemble(const std::vector<SceneRenderPart>& parts) const;
  ReferenceImage reference_image(unsigned threads = 0,
                                 const std::function<void(double fraction)>& progress = {}) const;

 private:
  const Scene& scene_;
  std::optional<CameraRays> camera_rays_;  // scene_.camera's frame, formed once (ray())
  unsigned threads_;
  std::unique_ptr<Shadowing> shadowing_;
  std::vector<std::unique_ptr<Effect>> effects_;
  std::vector<const EffectInfo*> infos_;
  std::vector<std::pair<double, double>> effect_setup_;  // per effect: wall, process CPU seconds
  double setup_seconds_ = 0.0;
  double setup_cpu_seconds_ = 0.0;
};

// The method an effect uses in this scene: scene.methods[name] or the effect's default.
MethodSpec effective_method(const Scene& scene, const EffectInfo& effect);

}  // namespace rayint
