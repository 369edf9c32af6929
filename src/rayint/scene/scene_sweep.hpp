#pragma once
// Error against cost of a scene's methods (`rayint scene-sweep`): the references of the named
// terms are computed once, on error_grid x error_grid pixels, then every configuration (a set of
// method overrides) renders the whole image (timed, as `rayint render` does) and is compared on
// those pixels. Used to find the two-pass method's speed-up over shadow rays at matched error.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rayint/scene/pipeline.hpp"

namespace rayint {

struct SweepPoint {
  std::map<std::string, MethodSpec> methods;  // the overrides of this configuration
  double render_seconds = 0.0;                // wall time of the whole image
  double setup_seconds = 0.0;                 // wall time of building the pipeline (light grid)
  double render_cpu_seconds = 0.0;            // process CPU time of the render
  double setup_cpu_seconds = 0.0;             // process CPU time of building the pipeline
  std::vector<EffectReport> effects;          // work and error per effect
  TermError total_error;
};

struct SceneSweepResult {
  int error_grid = 0;
  unsigned threads = 1;
  double reference_seconds = 0.0;  // wall time of the references
  std::vector<SweepPoint> points;
};

SceneSweepResult sweep_scene(const Scene& scene, const std::vector<std::map<std::string, MethodSpec>>& configs,
                        int error_grid, unsigned threads,
                        const std::function<void(std::size_t done, std::size_t total)>& progress = {});

}  // namespace rayint
