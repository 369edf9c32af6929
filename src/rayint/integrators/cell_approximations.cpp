// cell_approximations.cpp -- the closed-form approximations of Williams & Max (1992) Sec. 3.1,
// composited far -> near, each exactly as the paper defines it. Per channel, with I the light
// entering the far end of the cell (or piece) and L its length:
//
//   eq5  (Eq. 5, chromaticity constant): on each PIECE (segment part between transfer-function
//        breakpoints, where rho and kappa are linear) kappa is frozen at its piece average
//        (kappa_far + kappa_exit)/2 and int rho is exact, T = L (rho_far + rho_exit)/2:
//          I <- kappa (1 - e^{-T}) + I e^{-T}.
//        Because rho is linear on a piece, this is also Eq. 6 per piece; eq5 and eq6 differ only
//        where a segment contains breakpoints. Exact when kappa is constant along the ray.
//   eq6  (Eq. 6 with the paper's cell averages): on each CELL (segment), from its end values
//        only -- breakpoints inside the cell are ignored, as the paper's approximation does:
//          kappa_avg = (kappa(t1) + kappa(t2))/2,  rho_avg = (rho(t1) + rho(t2))/2,
//          I <- kappa_avg (1 - e^{-rho_avg L}) + I e^{-rho_avg L}.
//   eq7  (Eq. 7): the same cell averages, stored as one opacity per cell and channel,
//          alpha = 1 - e^{-x},  x = rho_avg L,  I <- kappa_avg alpha + (1 - alpha) I.
//        Mathematically Eq. 6; it differs only in that the transparency is 1 - alpha, whose
//        absolute error is up to 2^-53: relative error ~1.1e-16 e^{x}, and for x > 37.4
//        (e^{-x} < 2^-54) alpha rounds to 1 and the background is lost entirely (tested).
//   eq8  (Eq. 8): alpha = rho_avg L, clamped to 1 (the paper requires rho L << 1; the clamp keeps
//        the compositing an interpolation for thick cells), I <- kappa_avg alpha + (1 - alpha) I.
// Transmittance: the product over cells (pieces) of e^{-T}, e^{-rho_avg L} or 1 - alpha.
// Every 1 - e^{-x} is evaluated as -expm1(-x) (no cancellation for thin cells).
// Diagnostics: stat "pieces" (eq5) or "cells" (eq6..eq8); branch "alpha_clamped" (eq8, counted
// per cell and channel).
//
// Accuracy (tests/test_methods.cpp, [methods][limits]): with kappa and rho constant eq5, eq6 and
// eq7 equal Eq. 6 to 1e-14 relative and eq8 is within sum_cells x^2/2 max(kappa, I0) of it;
// with kappa constant and rho linear eq5 is exact to 1e-14 also across breakpoints; rho = 0
// returns the background unchanged. Elsewhere they are approximations, and their error is what
// `rayint eval` measures (e.g. 0.5%, 3.6%, 3.6%, 7% for eq5..eq8 on cases/smooth-convergence).
#include "rayint/integrators/cell_approximations.hpp"

#include <algorithm>
#include <cmath>

#include "rayint/model/pieces.hpp"

namespace rayint {

const char* cell_rule_name(CellRule rule) {
  switch (rule) {
    case CellRule::eq5:
      return "eq5";
    case CellRule::eq6:
      return "eq6";
    case CellRule::eq7:
      return "eq7";
    case CellRule::eq8:
      return "eq8";
  }
  return "?";
}

CellIntegrator::CellIntegrator(const TransferFunctions& tf, CellRule rule)
    : tf_(tf),
      rule_(rule),
      breakpoints_(rule == CellRule::eq5 ? tf.breakpoints() : std::vector<double>{}) {}

RayResult CellIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  RayResult r;
  r.intensity = ray.background;
  r.transmittance = {1.0, 1.0, 1.0};
  long cells = 0, clamped = 0;
  if (rule_ == CellRule::eq5) {
    thread_local std::vector<Piece> pieces;
    for (const auto& seg : ray.segments) {
      pieces.clear();
      append_pieces(tf_, seg, breakpoints_, pieces);
      for (const auto& p : pieces) {
        for (int c = 0; c < kChannels; ++c) {
          const double kappa = 0.5 * (p.kappa_far[c] + p.kappa_exit[c]);
          const double T = 0.5 * (p.rho_far[c] + p.rho_exit[c]) * p.length;
          const double transmittance = std::exp(-T);
          r.intensity[c] = kappa * -std::expm1(-T) + transmittance * r.intensity[c];
          r.transmittance[c] *= transmittance;
        }
        ++cells;
      }
    }
    if (diag) diag->add_stat("pieces", static_cast<double>(cells));
    return r;
  }
  for (const auto& seg : ray.segments) {
    if (!(seg.length > 0.0)) continue;  // a zero-length cell transmits everything
    ++cells;
    // The end values as limits from inside the cell (they differ from operator() only at a
    // transfer-function jump the cell starts or ends on).
    const bool up = seg.scalar_far < seg.scalar_exit, down = seg.scalar_far > seg.scalar_exit;
    for (int c = 0; c < kChannels; ++c) {
      const double kappa_avg =
          0.5 * (tf_.color[c].limit(seg.scalar_far, up) + tf_.color[c].limit(seg.scalar_exit, down));
      const double rho_avg =
          0.5 * (tf_.density[c].limit(seg.scalar_far, up) + tf_.density[c].limit(seg.scalar_exit, down));
      const double x = rho_avg * seg.length;
      double alpha, transparency;
      switch (rule_) {
        case CellRule::eq6:
          alpha = -std::expm1(-x);
          transparency = std::exp(-x);
          break;
        case CellRule::eq7:
          alpha = -std::expm1(-x);
          transparency = 1.0 - alpha;
          break;
        default:  // eq8
          alpha = x;
          if (alpha > 1.0) {
            alpha = 1.0;
            ++clamped;
          }
          transparency = 1.0 - alpha;
          break;
      }
      r.intensity[c] = kappa_avg * alpha + transparency * r.intensity[c];
      r.transmittance[c] *= transparency;
    }
  }
  if (diag) {
    diag->add_stat("cells", static_cast<double>(cells));
    if (rule_ == CellRule::eq8) diag->count("alpha_clamped", clamped);
  }
  return r;
}

}  // namespace rayint
