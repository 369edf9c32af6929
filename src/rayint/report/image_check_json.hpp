#pragma once
// The JSON diff of `rayint check CASE --candidate-image IMAGE` (README, "Checking a renderer's
// image"): verdict, pixel convention, tolerances, error figures, PSNR, the fraction within
// tolerance, the heat map's path and the worst pixels with their replayable case files (for a
// scene: the reference's own error and scene files holding each worst pixel's ray).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/render/image_compare.hpp"

namespace rayint {

struct ImageCheckContext {
  std::string case_name, case_source, candidate_source;
  double rel_tol = 0.0, abs_tol = 0.0;
  bool flip_x = false, flip_y = false;
  std::string alpha_mode;               // --candidate-alpha premultiplied|straight, empty when ignored
  std::string heat_map;                 // path written, or empty
  std::vector<std::string> worst_cases; // per worst pixel: its case file (empty: none written)
  std::string note;                     // e.g. why no case files were written
  // Mesh cases of cells other than tetrahedra: "own" (their own interpolation) or "split" (VTK's
  // split); empty for tetrahedra and scenes (no "mode" field then).
  std::string mode;
  long failed_pixels = 0;               // own mode: expected pixels that are not a result (NaN)
  // Monte Carlo mode (--candidate-variance): the z-test decides; null otherwise.
  const ZTestResult* z_test = nullptr;
  double alpha = 0.0, min_fraction = 0.0;
  long samples = 0;                     // 0: the variance image is already of the mean
  std::string variance_source;
  // A scene (`rayint check SCENE --candidate-image`): the expected image is the scene's reference
  // image (scene/pipeline.hpp ReferenceImage), and the worst pixels are scene files with that
  // pixel's ray. Null for a mesh case.
  struct SceneReference {
    std::string image;               // the reference image written to the artifacts, or empty
    double max_error = 0.0;          // the references' own largest error estimate (absolute)
    long long unconverged = 0;       // pixels where a reference did not converge
    long long evaluations = 0;
    double seconds = 0.0;
    bool variance_added = false;     // z-test: (error / 2)^2 added to the candidate's variance
  };
  const SceneReference* scene_reference = nullptr;
};

// The pixel convention in one sentence, as the README states it (printed in every diff).
const char* pixel_convention_text();

// Non-finite numbers are written as null (PSNR of identical images: "inf" as a string).
// The verdict ("pass") is the z-test's in Monte Carlo mode, the tolerance rule's otherwise.
nlohmann::ordered_json image_check_json(const ImageCheckContext& context, const ImageComparison& c);
std::string image_check_summary_line(const ImageCheckContext& context, const ImageComparison& c);

}  // namespace rayint
