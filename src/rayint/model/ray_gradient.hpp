#pragma once
// The gradient of a ray's intensity with respect to every input of the ray (issue 28): the
// background, each segment's length and two end scalars, and the position and value of every
// node of the six transfer functions. Channel c's intensity depends only on background c,
// density[c] and color[c] (and on the segments, shared by all channels), so the Jacobian is
// stored per channel: entry [c] of a segment or background block is dI_c/d(that input), and the
// node blocks of channel c hold dI_c/d(nodes of density[c] or color[c]).
//
// Convention at a kink (docs/gradients.md). I is differentiable in every input except where a
// segment of constant scalar (scalar_far == scalar_exit) sits exactly on a node of a transfer
// function; there the reported derivative is the one of the interval to the right of the node
// (larger scalars) -- the interval PiecewiseLinear's upper_bound lookup picks: d/ds is the
// right-hand derivative in that segment's scalar, d/dp the left-hand one in the node position.
// Every other coincidence (a segment end on a node, two functions' nodes at one position) is a
// point where I is differentiable, and the reported derivative is the two-sided one.
//
// Jumps (a node scalar stored twice: left value, right value; docs/gradients.md, "Jumps").
// I is differentiable in both values of a jump (each is a node value of the linear piece beside
// it) and in the jump's position x_j, which moves the points where the ray's scalar crosses x_j.
// The two nodes of a jump share one position; their position entries are TIED: the first
// (left-value) node's entry holds dI/dx_j, the derivative for moving both nodes together (the
// only motion that keeps the jump a jump), and the second node's entry is 0. So the chain rule
// sum_k dI/dp_k dp_k/dtheta over any parameterisation that keeps the jump (both nodes follow the
// same theta, as a preset's point does) is right; a candidate for `rayint gradcheck` reports the
// same. Where the derivative does not exist the entry is NaN (null in JSON) and `undefined` says
// why: a segment end (of a segment with non-zero length and non-constant scalar) exactly on x_j,
// or a segment of constant scalar x_j (the ray touches the jump tangentially: moving x_j or that
// scalar one way changes I to first order, the other way not), for x_j's position entry and that
// segment end's scalar entry, in the channel whose function jumps; and x_j's position entry where
// density[c] and color[c] both jump at x_j (moving one of the two jumps alone is not differentiable).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "rayint/model/ray.hpp"

namespace rayint {

// Which blocks a ray gradient computes: all of them, or the segment blocks only (intensity,
// background, length, scalar_far, scalar_exit; the node blocks left empty), what a loss with
// respect to the scene's scalars or geometry needs (render/mesh_gradient.hpp).
enum class GradientBlocks { all, segments };

struct NodeDerivative {
  double position = 0.0;  // dI_c / d scalar of the node
  double value = 0.0;     // dI_c / d value of the node
};

struct RayGradient {
  Rgb intensity{};                       // the forward intensity the gradient belongs to
  Rgb background{};                      // dI_c / d background_c
  std::vector<Rgb> length;               // [segment][c] dI_c / d length
  std::vector<Rgb> scalar_far;           // [segment][c] dI_c / d scalar_far
  std::vector<Rgb> scalar_exit;          // [segment][c] dI_c / d scalar_exit
  std::array<std::vector<NodeDerivative>, kChannels> density;  // [c][node] of density[c]
  std::array<std::vector<NodeDerivative>, kChannels> color;    // [c][node] of color[c]
  // Empty, or why some entries are NaN (derivatives that do not exist, at a jump: see above).
  std::string undefined;

  // Zeroed blocks shaped for `tf` and `ray`.
  static RayGradient zeros(const TransferFunctions& tf, const Ray& ray);
  // Makes this zeros(tf, ray), keeping the storage.
  void reset(const TransferFunctions& tf, const Ray& ray);
  // The largest |entry| of channel c over every block (the scale of the pass rule and of the
  // relative errors); NaN if an entry is NaN, except the entries `undefined` explains, which are
  // skipped when it is non-empty.
  double channel_scale(int c) const;
  // Whether every entry of every block and channel is finite (channel_scale of each channel is
  // then finite too, with `undefined` empty): one pass, no per-entry callback.
  bool all_finite() const;
  // Calls f(entry_c, block, index, parameter) over channel c's entries in a fixed order:
  // background; length, scalar_far, scalar_exit per segment; density, color per node
  // (parameter "position" / "value"; "" for the segment and background blocks).
  template <class F>
  void for_each(int c, F&& f) const {
    f(background[c], "background", std::size_t{0}, "");
    for (std::size_t j = 0; j < length.size(); ++j) f(length[j][c], "length", j, "");
    for (std::size_t j = 0; j < scalar_far.size(); ++j) f(scalar_far[j][c], "scalar_far", j, "");
    for (std::size_t j = 0; j < scalar_exit.size(); ++j) f(scalar_exit[j][c], "scalar_exit", j, "");
    for (std::size_t k = 0; k < density[c].size(); ++k) {
      f(density[c][k].position, "density", k, "position");
      f(density[c][k].value, "density", k, "value");
    }
    for (std::size_t k = 0; k < color[c].size(); ++k) {
      f(color[c][k].position, "color", k, "position");
      f(color[c][k].value, "color", k, "value");
    }
  }
};

// Where a scalar s lies in a piecewise-linear function, for differentiating f(s) at a piece end:
// the interval is chosen by `lo`, the smaller scalar of the piece (no breakpoint lies strictly
// inside a piece, so the whole piece is in that interval; lo itself on a node means the interval
// to its right, the kink convention above).
struct NodeWeights {
  // f(s) = sum of w[i] * value[node[i]]; df/ds = slope; df/d position[node[i]] = dp[i].
  std::size_t node[2] = {0, 0};
  double w[2] = {0.0, 0.0};
  double dp[2] = {0.0, 0.0};
  double slope = 0.0;
  int count = 0;  // 1 (constant: below the first node, above the last, one node) or 2
};
NodeWeights node_weights(const PiecewiseLinear& f, double lo, double s);
// The same with k = upper_bound(f.scalar, lo) known to the caller (no search), bit for bit.
NodeWeights node_weights_in(const PiecewiseLinear& f, std::size_t k, double s);
// df/ds of that interval (node_weights' slope; 0 on the constant extensions).
inline double interval_slope(const PiecewiseLinear& f, std::size_t k) {
  if (k == 0 || k == f.scalar.size()) return 0.0;
  return (f.value[k] - f.value[k - 1]) / (f.scalar[k] - f.scalar[k - 1]);
}

// The first node of f's jump at scalar x (nodes i, i + 1 both at x), or kNoJump.
inline constexpr std::size_t kNoJump = static_cast<std::size_t>(-1);
std::size_t jump_node(const PiecewiseLinear& f, double x);

// The tie of a jump's two position entries (see above): for every jump (nodes i, i+1 at one
// scalar) of each function, position[i] += position[i+1] and position[i+1] = 0.
void tie_jump_positions(const TransferFunctions& tf, std::array<std::vector<NodeDerivative>, kChannels>& density,
                        std::array<std::vector<NodeDerivative>, kChannels>& color);

}  // namespace rayint
