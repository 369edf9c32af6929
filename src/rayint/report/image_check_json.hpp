#pragma once
// The JSON diff of `rayint check CASE --candidate-image IMAGE` (README, "Checking a renderer's
// image"): verdict, pixel convention, tolerances, error figures, PSNR, the fraction within
// tolerance, the heat map's path and the worst pixels with their replayable case files.
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
  // Monte Carlo mode (--candidate-variance): the z-test decides; null otherwise.
  const ZTestResult* z_test = nullptr;
  double alpha = 0.0, min_fraction = 0.0;
  long samples = 0;                     // 0: the variance image is already of the mean
  std::string variance_source;
};

// The pixel convention in one sentence, as the README states it (printed in every diff).
const char* pixel_convention_text();

// Non-finite numbers are written as null (PSNR of identical images: "inf" as a string).
// The verdict ("pass") is the z-test's in Monte Carlo mode, the tolerance rule's otherwise.
nlohmann::ordered_json image_check_json(const ImageCheckContext& context, const ImageComparison& c);
std::string image_check_summary_line(const ImageCheckContext& context, const ImageComparison& c);

}  // namespace rayint
