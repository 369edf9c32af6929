#pragma once
// `rayint check CASE --candidate-image IMAGE`: a renderer's image against the exact image of the
// case's camera (check_image.cpp; library: render/image_compare.hpp).
#include <string>

#include "rayint/input/mesh_case_reader.hpp"

namespace rayint::cli {

struct ImageCheckOptions {
  std::string case_file;
  MeshReadOptions mesh;  // --strict-mesh, --cells own|split
  std::string candidate_image;
  std::string candidate_variance;  // Monte Carlo: per-pixel variance of the candidate's mean
  long samples = 0;                // Monte Carlo: samples per pixel; the variance image is then per sample
  double rel_tol = 1e-6, abs_tol = 0.0;
  bool flip_x = false, flip_y = false;
  std::string alpha_mode = "ignore";  // --candidate-alpha: ignore | premultiplied | straight
  int worst = 3;
  std::string artifacts;  // heat map, worst-pixel case files (and a scene's reference.npy); empty: none
  std::string output;              // JSON diff; empty: stdout
  std::string junit;               // JUnit XML; empty: none
  unsigned threads = 0;
  bool quiet = false;
  double alpha = 0.01;             // z-test: family significance level
  double min_fraction = 0.9975;    // z-test: pass when at least this fraction of tests pass (Mitsuba 3's)
};

// Writes the diff and files; throws ChecksFailed when the check fails, InputError on bad input.
void run_image_check(const ImageCheckOptions& options);

}  // namespace rayint::cli
