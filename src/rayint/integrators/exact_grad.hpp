#pragma once
// Exact derivatives of the exact piece integral (integrators/exact.hpp) and of a ray's intensity
// with respect to every input of the ray (issue 28). See exact_grad.cpp for the forms by region
// and docs/gradients.md for the mathematics, the conventions at kinks and the measured accuracy.
#include <memory>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

// How the two moments M1, M2 of a piece were formed (branch introspection).
enum class MomentMethod {
  transparent,      // T == 0: M1 = 1/2, M2 = 1/3
  midpoint_series,  // Taylor series about u = 1/2 (the thin branch's, differentiated term by term)
  q2_series,        // series in B with the moments m_n(A) (the q2 branch's, term by term)
  identity,         // from e0 by integration by parts (erfcx branch, z0 <= kMomentCfFrom)
  continued_fraction,  // erfcx branch, z0 > kMomentCfFrom: ratios g_n/g_{n-1} by their fraction
  exit_series,      // dawson branch, T <= kMomentAsymptoticDepth: series in |B| about u = 0
  asymptotic,       // dawson branch, T > kMomentAsymptoticDepth: Laplace series at y0
};
const char* moment_method_name(MomentMethod m);

// Thresholds of the derivative (origin in exact_grad.cpp).
inline constexpr double kMomentCfFrom = 1.0;             // z0 above which the fraction is used
inline constexpr double kMomentAsymptoticDepth = 50.0;   // T above which e^{-T} terms are dropped

// One channel of one piece: its optics (exact_piece's, bit for bit) and their derivatives with
// respect to the piece's five inputs.
struct PieceOpticsGrad {
  PieceOptics optics;
  // d emission / d (length, rho_far, rho_exit, kappa_far, kappa_exit)
  double de_length = 0.0, de_rho_far = 0.0, de_rho_exit = 0.0, de_kappa_far = 0.0,
         de_kappa_exit = 0.0;
  // d transmittance / d (length, rho_far, rho_exit); it does not depend on kappa
  double dt_length = 0.0, dt_rho_far = 0.0, dt_rho_exit = 0.0;
  // The moments behind them: e0 = int_0^1 e^{-tau}, M_n = int_0^1 u^n e^{-tau} du.
  double e0 = 1.0, m1 = 0.5, m2 = 1.0 / 3.0;
  MomentMethod method = MomentMethod::transparent;
  int terms = 0;           // series or fraction terms used for the moments
  bool converged = true;   // false if a series hit its budget
};

PieceOpticsGrad exact_piece_grad(const ChannelPiece& piece);
// The same with kappa_far - kappa_exit given (the ray gradient passes slope * (s_far - s_exit),
// exact to a few ulps, where the difference of the two rounded end values is not).
PieceOpticsGrad exact_piece_grad(const ChannelPiece& piece, double kappa_far_minus_exit);
// The same for a piece whose length, rho_far and rho_exit are those `same_depth` was computed for
// (another channel of a grey medium, TransferFunctions::grey): its transmittance, weights and
// moments are taken from it and only the entries that depend on kappa are formed, bit for bit
// what the call above returns (tests/test_grad.cpp).
PieceOpticsGrad exact_piece_grad(const ChannelPiece& piece, double kappa_far_minus_exit,
                                 const PieceOpticsGrad& same_depth);

// What a ray gradient needs of one piece-channel's PieceOpticsGrad: its optics and their
// derivatives (d transmittance / d rho_far and d rho_exit are equal: dt_rho).
struct PieceDerivatives {
  double transmittance = 1.0, emission = 0.0;
  double de_length = 0.0, de_rho_far = 0.0, de_rho_exit = 0.0, de_kappa_far = 0.0, de_kappa_exit = 0.0;
  double dt_length = 0.0, dt_rho = 0.0;
};
inline PieceDerivatives derivatives_of(const PieceOpticsGrad& g) {
  return {g.optics.transmittance, g.optics.emission, g.de_length,  g.de_rho_far, g.de_rho_exit,
          g.de_kappa_far,         g.de_kappa_exit,   g.dt_length, g.dt_rho_far};
}

// exact_piece_grad on n pieces at once, through exact_batch (integrators/exact_batch.hpp): the
// emission weights and the thin_series moments from its vector kernels (the same branches,
// thresholds, series and stop), the other branches' moments by the functions exact_piece_grad
// uses, the transmittance exp(-T) from special::exp_neg_array (vectors, std::exp's accuracy
// class: at most ~0.52 ulp; it differs from exact_piece's std::exp in the last bit for ~0.3% of
// arguments). Within
// GradTolerances::batch_vs_scalar_rel of exact_piece_grad's (tests/test_grad_batch.cpp), bit for
// bit neither exact path's. With same_depth_stride s > 1, pieces i with i % s != 0 have the
// length, rho_far and rho_exit of piece i - i % s (a grey medium's channels): only every s-th
// piece goes through the batch, the others reuse its weights and moments, as the same_depth
// overload above.
void exact_pieces_grad(const ChannelPiece* pieces, const double* kappa_far_minus_exit, std::size_t n,
                       PieceDerivatives* out, int same_depth_stride = 1);
// The same on pieces given as columns (entry i of each column: piece i), read in place.
void exact_pieces_grad(const PieceColumns& pieces, const double* kappa_far_minus_exit, PieceDerivatives* out,
                       int same_depth_stride = 1);

namespace detail {
class GradientPreparation;
}

// The gradient of every channel's intensity with respect to every input of the ray, for transfer
// functions prepared once (a copy of them, their PieceSplitter and per-function tables), as
// ExactIntegrator holds its splitter: for many rays with the same functions (images, losses).
// Its pieces go through exact_pieces_grad's arithmetic (bit for bit its entries: the batch's
// columns are kept for the ray and each piece's derivatives formed where the reverse pass uses
// them, exact_grad.cpp's ExactPieceSource); the forward intensity composites exact_piece's
// transmittance with exact_batch's emission: within GradTolerances::forward_rel (2.5e-15
// relative; 1.1e-15 measured) of both exact paths, bit for bit neither (tests/test_grad.cpp).
// Pieces are those of append_pieces (model/pieces.hpp); compositing far -> near is
// differentiated in reverse. Throws std::invalid_argument for a non-finite segment length or
// scalar or background. Copies share the preparation; calls may run on several threads at once.
class ExactRayGradient {
 public:
  explicit ExactRayGradient(const TransferFunctions& tf);
  RayGradient operator()(const Ray& ray) const;
  // The same into `out`, reusing its storage (no allocation per ray once warm). With
  // GradientBlocks::segments the node blocks are not computed (left empty): what an image loss
  // with respect to the scene's scalars needs, at a lower cost; every other entry is the same,
  // bit for bit.
  void operator()(const Ray& ray, RayGradient& out, GradientBlocks blocks = GradientBlocks::all) const;

 private:
  std::shared_ptr<const detail::GradientPreparation> prep_;
};

// ExactRayGradient's gradient without a prepared object: the same code, with a preparation kept
// per thread for the last transfer functions seen (compared point for point; rebuilt when they
// change, a cost per ray when every ray has its own functions).
RayGradient exact_ray_gradient(const TransferFunctions& tf, const Ray& ray);
void exact_ray_gradient(const TransferFunctions& tf, const Ray& ray, RayGradient& out,
                        GradientBlocks blocks = GradientBlocks::all);

}  // namespace rayint
