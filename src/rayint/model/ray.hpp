#pragma once
// Rays as the case files describe them: segments run from the far end (where the background
// enters, t0) toward the eye; along a segment the scalar varies linearly (Williams & Max Eq. 13).
//
// The two ends of a ray piece (a segment, a piece of model/pieces.hpp, a table step) are named
// the same way everywhere in model/, integrators/, reference/ and the tables:
//   far   where light enters the piece, away from the eye (scalar_far, rho_far, s_far, ...);
//   exit  where light leaves it, toward the eye (scalar_exit, rho_exit, s_exit, ...).
// Sequences run far -> near, from the background toward the eye. A case file's segment
// "scalar": [a, b] is [scalar_far, scalar_exit].
#include <string>
#include <vector>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct Segment {
  double length = 0.0;       // > 0 (0 allowed: contributes nothing)
  double scalar_far = 0.0;   // scalar at the far end, where the segment starts
  double scalar_exit = 0.0;  // scalar at the exit end, toward the eye
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
