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
#include <array>
#include <cstddef>
#include <vector>

#include "rayint/model/ray.hpp"

namespace rayint {

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

  // Zeroed blocks shaped for `tf` and `ray`.
  static RayGradient zeros(const TransferFunctions& tf, const Ray& ray);
  // Makes this zeros(tf, ray), keeping the storage.
  void reset(const TransferFunctions& tf, const Ray& ray);
  // The largest |entry| of channel c over every block (the scale of the pass rule and of the
  // relative errors).
  double channel_scale(int c) const;
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

}  // namespace rayint
