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
#include <cstddef>
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
  // Quadratic chords (a straight-edged quadratic tetrahedron's scalar along a ray,
  // mesh/quadratic_tets.hpp): empty for a ray of linear segments (every case file); otherwise one
  // coefficient per segment, and the scalar at distance s from segment i's far end is
  //   scalar_far + (scalar_exit - scalar_far) s / length + quadratic[i] s (s - length)
  // (segment_scalar): the ends stay scalar_far and scalar_exit. Only the methods that say so
  // (RayIntegrator::takes_quadratic_segments) integrate such a ray; the others refuse it.
  std::vector<double> quadratic{};
};

// True when some segment of `ray` has a non-zero quadratic coefficient.
inline bool has_quadratic_segments(const Ray& ray) {
  for (double q : ray.quadratic)
    if (q != 0.0) return true;
  return false;
}

// The scalar of segment i of `ray` at distance s from its far end (linear when the ray has no
// quadratic coefficients).
inline double segment_scalar(const Ray& ray, std::size_t i, double s) {
  const Segment& seg = ray.segments[i];
  const double q = i < ray.quadratic.size() ? ray.quadratic[i] : 0.0;
  const double linear = seg.length > 0.0 ? seg.scalar_far + (seg.scalar_exit - seg.scalar_far) * (s / seg.length)
                                         : seg.scalar_far;
  return linear + q * s * (s - seg.length);
}

struct Case {
  std::string name;
  std::string description;
  std::string source;  // file it was read from, for messages
  TransferFunctions transfer;
  std::vector<Ray> rays;
};

}  // namespace rayint
