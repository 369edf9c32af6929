#pragma once
// The emission-absorption integral (Williams & Max 1992, Eq. 4, transfer functions of Sec. 3.1)
// of a voxel grid's TRILINEAR interpolant, in double, to near machine precision: what VTK's
// image mappers and every image renderer mean by "the volume", with no sampling.
//
// Method (trilinear_integral.cpp):
//  1. Cubes: trilinear_cubics (voxel_grid.hpp) walks the cubes the ray crosses (3D DDA on the
//     planes x_i = k) and gives the scalar in each as the exact cubic f(s).
//  2. Pieces: where a transfer function changes slope (its breakpoints) f must be cut. The
//     range of f on the cube is bounded by the convex hull of its Bernstein coefficients; when
//     no breakpoint lies strictly inside that bound (most cubes) the cube is one piece, since
//     rho(f) and kappa(f) are then one linear function of f and so cubics in s, whether or not
//     f is monotone. Otherwise poly::split_points (model/polynomial.hpp: critical points, then
//     TOMS 748 on each monotone stretch for every breakpoint crossed) cuts it.
//  3. On a piece of length h, u the distance from its far end: rho(u) is a cubic, the optical
//     depth tau(u) = int_0^u rho is its exact antiderivative (a quartic, no quadrature), T =
//     tau(h), and the light leaving is I exp(-T) + E with
//       E = kappa(h) (1 - exp(-T)) + int_0^h (kappa(u) - kappa(h)) rho(u) exp(-(T - tau(u))) du,
//     the first term exact (-expm1), the second (zero for a constant kappa) by composite
//     8-point Gauss-Legendre on panels of optical depth <= kPanelDepth (panel count from a bound
//     of rho on the piece), starting where the depth to the exit falls below kTailDepth.
// Thresholds: kPanelDepth = 0.5 and 8 nodes were chosen by measurement (tests [trilinear]):
//   8-point GL is exact for kappa rho (degree 6) times a constant, and with exp(-tau) varying by
//   <= e^0.5 per panel the measured error stays at rounding level; kTailDepth = 50: the skipped
//   part is below max kappa * exp(-50) = 2e-22 max kappa (absolute).
// Measured accuracy (tests/test_trilinear.cpp, [trilinear], 208 rays incl. rays in grid planes,
// along edges and through vertices, optical depths 0.5 to 100) against the 50-digit polynomial
// reference (reference/poly_reference.hpp) on the same cubics: worst relative error 7.4e-16 of
// the intensity, 1.5e-14 of the transmittance (eps * T at T ~ 100).
#include <array>
#include <string>
#include <vector>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/model/poly_ray.hpp"
#include "rayint/model/ray_gradient.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct TrilinearRayResult {
  Rgb intensity{0.0, 0.0, 0.0};     // at the eye
  Rgb transmittance{1.0, 1.0, 1.0};  // exp(-total optical depth) per channel
  long cubes = 0;                    // cubes (segments) crossed
  long pieces = 0;                   // pieces integrated (>= cubes with non-zero length)
  long split_cubes = 0;              // cubes cut at a transfer-function breakpoint
};

// The gradient of one ray's trilinear integral (TrilinearIntegrator::gradient): per channel c,
// dI_c with respect to the background, every grid point value the ray's cubes touch (sparse,
// ascending index; the others are 0), and every transfer-function node's position and value
// (density[c] and color[c], like model/ray_gradient.hpp's node blocks, with its convention at a
// jump: the first node of a jump carries dI/d(jump position), the second 0; NaN where the
// derivative does not exist, with the reason in `undefined`).
struct TrilinearGradient {
  Rgb intensity{};   // the forward intensity (integrate()'s, bit for bit)
  Rgb background{};  // dI_c / d background_c = transmittance
  std::vector<std::size_t> index;  // grid points with a derivative (ascending)
  std::vector<Rgb> d_value;        // [i][c] dI_c / d value of point index[i]
  std::array<std::vector<NodeDerivative>, kChannels> density, color;
  std::string undefined;  // empty, or why some entries are NaN (the ray touches a jump)
  // Largest |entry| of channel c over the voxel and node blocks (NaN entries skipped when
  // `undefined` explains them).
  double channel_scale(int c) const;
};

class TrilinearIntegrator {
 public:
  static constexpr double kPanelDepth = 0.5;
  static constexpr double kTailDepth = 50.0;

  explicit TrilinearIntegrator(const TransferFunctions& tf);
  // The ray through the grid's trilinear interpolant; `background` enters at the far end.
  TrilinearRayResult integrate(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background) const;
  // Any ray of segments of degree <= 3 (e.g. trilinear_ray's); throws std::invalid_argument
  // for a higher degree or a negative or non-finite length.
  TrilinearRayResult integrate(const PolyRay& ray) const;
  // Emission without absorption, int kappa rho ds per channel (a scene's emission effect with
  // absorption off): on each piece kappa rho is a polynomial of degree 6, integrated exactly
  // (up to rounding) by 8-point Gauss-Legendre.
  Rgb emission_only(const VoxelGrid& grid, const ViewRay& ray) const;
  // The derivative of integrate(grid, ray, background) with respect to every grid point value,
  // transfer-function node and the background (see trilinear_integral.cpp, "Gradient").
  TrilinearGradient gradient(const VoxelGrid& grid, const ViewRay& ray, const Rgb& background) const;

 private:
  void add_segment(const std::array<double, 4>& c, double length, TrilinearRayResult& r,
                   Rgb* emission_only) const;
  void add_piece(const std::array<double, 4>& g, double h, double f_mid, TrilinearRayResult& r,
                 Rgb* emission_only) const;

  const TransferFunctions* tf_;
  std::vector<double> breakpoints_;
  bool grey_ = false;
};

}  // namespace rayint
