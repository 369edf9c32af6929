#pragma once
// Direction bins on the faces of a cube (Max 1995, Sec. 7: "direction bins arranged on the
// exterior faces of a block of cubes"): each face of [-1, 1]^3 is cut into n x n squares, giving
// 6 n^2 bins of unequal solid angle. Each bin has its centre direction, its exact solid angle
//   Omega = sum over corners (+-) atan(x y / sqrt(1 + x^2 + y^2))
// (the rectangle [x1, x2] x [y1, y2] on the plane at distance 1), and s x s sub-directions with
// their own exact solid angles, which are used to average the phase function over bins.
// The solid angles add to 4 pi to rounding (tested).
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/optics/phase.hpp"

namespace rayint {

struct DirectionBin {
  Vec3 center;            // unit
  double solid_angle = 0;
  std::vector<Vec3> sub_directions;      // unit
  std::vector<double> sub_solid_angles;  // summing to solid_angle
};

std::vector<DirectionBin> cube_face_bins(int n_per_edge, int sub_per_edge);

// Bin-to-bin phase matrix, row b_in, column b_out:
//   P[b_in][b_out] = (1/Omega_in) int_{b_in} int_{b_out} p(w_in . w_out) dw_out dw_in,
// the fraction of light arriving in bin b_in that scatters into bin b_out, by the sub-direction
// sums, each row renormalized to sum 1 (conservation, Max: unequal solid angles are accounted
// for in the matrix). Row-major, bins x bins.
std::vector<double> bin_phase_matrix(const std::vector<DirectionBin>& bins, const PhaseFunction& p);

// Fraction of light arriving along `w_in` (unit) that scatters into each bin:
//   int_{bin} p(w_in . w) dw, by the sub-direction sums, renormalized to sum 1.
std::vector<double> bin_phase_from(const std::vector<DirectionBin>& bins, const PhaseFunction& p,
                                   const Vec3& w_in);

}  // namespace rayint
