#pragma once
// Rays as the case files describe them: segments run from the far end (where the background
// enters, t0) toward the eye; along a segment the scalar varies linearly (Williams & Max Eq. 13).
#include <string>
#include <vector>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct Segment {
  double length = 0.0;      // > 0 (0 allowed: contributes nothing)
  double scalar_far = 0.0;  // scalar where the segment starts (far end)
  double scalar_near = 0.0; // scalar where it ends (toward the eye)
};

struct Ray {
  Rgb background{0.0, 0.0, 0.0};  // intensity entering at the far end
  std::vector<Segment> segments;  // far -> near
};

struct Case {
  std::string name;
  std::string description;
  std::string source;  // file it was read from, for messages
  TransferFunctions transfer;
  std::vector<Ray> rays;
};

}  // namespace rayint
