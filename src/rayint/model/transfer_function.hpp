#pragma once
// The six user transfer functions of Williams & Max (1992, Sec. 3.1): optical density rho and
// chromaticity kappa for r, g, b, each piecewise linear in the scalar and constant beyond its
// first and last point.
//
// Jumps: a scalar may appear twice in a row (never three times); the two points are the left
// and right values of a discontinuity there (a ParaView step, a duplicated node). Every integral
// is split at breakpoints, and each piece uses the one-sided limits from inside it (limit()):
// a scalar that crosses the jump along a segment switches value exactly there. The value AT the
// jump scalar itself (operator()) is the left one, as VTK's lookup returns the first of two
// repeated nodes; it matters only on a measure-zero set -- a sampling method that hits the jump
// scalar exactly, or a segment whose scalar is constant and equal to the jump scalar, which takes
// that left value along its whole length (docs/transfer-function-conventions.md, "Jumps").
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace rayint {

using Rgb = std::array<double, 3>;
inline constexpr int kChannels = 3;

struct PiecewiseLinear {
  std::vector<double> scalar;  // non-decreasing; a scalar at most twice in a row (a jump)
  std::vector<double> value;   // finite, >= 0; same size as scalar, at least one point

  // Linear interpolation; the end value holds outside [scalar.front(), scalar.back()].
  // At a breakpoint it returns the stored value exactly (at a jump, the left one).
  double operator()(double s) const;
  // The one-sided limit at s: from below (from_above false) or from above. Equal to operator()
  // except at a jump, where it is the left or the right value.
  double limit(double s, bool from_above) const;
  // The same with its search done by the caller: k = upper_bound(scalar, s) from above,
  // lower_bound from below (PieceSplitter::reset walks them along its sorted breakpoints).
  double limit(double s, bool from_above, std::size_t k) const;
  // operator() for scalar.front() < s < scalar.back() with k such that scalar[k-1] <= s <
  // scalar[k] (the index upper_bound(scalar, s) returns), known to the caller: the same
  // arithmetic, bit for bit.
  double interpolate(double s, std::size_t k) const;
  // True when some scalar repeats (the function jumps there).
  bool has_jump() const;
};

// Empty when f is a valid function (matching non-empty lists, finite scalars non-decreasing and
// at most twice in a row, finite values >= 0); else what is wrong, for a message.
std::string check_points(const PiecewiseLinear& f);

struct TransferFunctions {
  std::array<PiecewiseLinear, kChannels> density;  // rho_r, rho_g, rho_b
  std::array<PiecewiseLinear, kChannels> color;    // kappa_r, kappa_g, kappa_b

  // Sorted, de-duplicated union of the breakpoints of all six functions.
  std::vector<double> breakpoints() const;
  // The same into `out` (its storage reused).
  void breakpoints_into(std::vector<double>& out) const;
  // True when the three densities are the same function, point for point and bit for bit (a grey
  // medium, as from one opacity transfer function): every channel of a piece then has the same
  // optical depth, so its transmittance and emission weights need computing only once.
  bool grey() const;
  // True when one of the six functions jumps (PiecewiseLinear::has_jump).
  bool has_jump() const;
};

}  // namespace rayint
