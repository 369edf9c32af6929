#pragma once
// Rays whose scalar is a polynomial along each segment: what the higher-order cells of
// Williams & Max (1992, appendix: quadratic tetrahedra, trilinear and quadratic bricks) and the
// trilinear interpolant of a voxel grid give along a straight ray. The closed form of Sec. 3.3
// needs a linear scalar (Eq. 13); these rays go to the polynomial reference
// (reference/poly_reference.hpp) and the ODE method (cells/poly_integrate.hpp) instead.
// Orientation as in model/ray.hpp: segments run far -> near, and the polynomial's variable s is
// the distance from the segment's far end toward the eye.
#include <cstddef>
#include <vector>

#include "rayint/model/ray.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct PolySegment {
  double length = 0.0;          // >= 0
  std::vector<double> coeffs;   // scalar(s) = sum_k coeffs[k] s^k, s in [0, length]

  double operator()(double s) const {  // Horner
    double f = 0.0;
    for (std::size_t k = coeffs.size(); k-- > 0;) f = f * s + coeffs[k];
    return f;
  }
  int degree() const { return coeffs.empty() ? 0 : static_cast<int>(coeffs.size()) - 1; }
};

struct PolyRay {
  Rgb background{0.0, 0.0, 0.0};      // intensity entering at the far end
  std::vector<PolySegment> segments;  // far -> near
};

// A Ray of linear or quadratic segments (model/ray.hpp, Ray::quadratic) as polynomials in the
// distance s from each segment's far end: scalar_far + (g - q L) s + q s^2 with g the chord's
// slope (scalar_exit - scalar_far) / L.
inline PolyRay to_poly_ray(const Ray& ray) {
  PolyRay out;
  out.background = ray.background;
  out.segments.reserve(ray.segments.size());
  for (std::size_t i = 0; i < ray.segments.size(); ++i) {
    const Segment& seg = ray.segments[i];
    const double q = i < ray.quadratic.size() ? ray.quadratic[i] : 0.0;
    const double g = seg.length > 0.0 ? (seg.scalar_exit - seg.scalar_far) / seg.length : 0.0;
    if (q == 0.0)
      out.segments.push_back(PolySegment{seg.length, {seg.scalar_far, g}});
    else
      out.segments.push_back(PolySegment{seg.length, {seg.scalar_far, g - q * seg.length, q}});
  }
  return out;
}

}  // namespace rayint
