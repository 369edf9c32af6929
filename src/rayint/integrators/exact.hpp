#pragma once
// The exact emission-absorption integral (Williams & Max 1992, Eq. 4 and Sec. 3.3) on a piece
// where rho and kappa are linear, in forms that stay accurate in every regime. See exact.cpp.
#include "rayint/integrators/integrator.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {

enum class ExactBranch {
  transparent,  // T == 0: nothing absorbed or emitted
  thin_series,  // 0 < T <= kThinDepth: Taylor series of exp(-tau), no cancellation
  q2_series,    // T > kThinDepth, |B| <= kQ2Relative * A^2 (includes q2 == 0 exactly)
  erfcx,        // T > kThinDepth, density decreasing toward the eye (paper's q2 < 0)
  dawson,       // T > kThinDepth, density increasing toward the eye (paper's q2 > 0)
};
const char* branch_name(ExactBranch b);

struct PieceOptics {
  double transmittance = 1.0;  // exp(-T)
  double emission = 0.0;       // int kappa rho exp(-tau) ds
  double weight_exit = 0.0;    // emission = kappa_exit * weight_exit + kappa_far * weight_far
  double weight_far = 0.0;
  ExactBranch branch = ExactBranch::transparent;
  int terms = 0;               // series terms used (0 for closed forms)
  bool converged = true;       // false if a series hit its term budget
};

// Thresholds (their origin and measured effect are documented in exact.cpp).
inline constexpr double kThinDepth = 1.0;
inline constexpr double kQ2Relative = 1.0 / (1 << 26);

PieceOptics exact_piece(const ChannelPiece& piece);

// Composites the exact piece integral over the pieces of a ray (far -> near). By default all
// pieces and channels of the ray go through exact_batch (integrators/exact_batch.hpp) at once;
// Path::scalar calls exact_piece one piece-channel at a time (the readable reference, method
// "exact:path=scalar").
class ExactIntegrator final : public PieceIntegrator {
 public:
  enum class Path { batch, scalar };
  explicit ExactIntegrator(const TransferFunctions& tf, Path path = Path::batch)
      : PieceIntegrator(tf), path_(path) {}
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 protected:
  // The batch path for a grey medium: the pieces of all n rays in one kernel batch (fewer, fuller
  // vectors than a batch per ray; each piece's result is the same), counting the pieces;
  // otherwise ray by ray, not counting them.
  bool integrate_many_segments(const Ray* rays, std::size_t n, RayResult* out, long* pieces) const override;

 private:
  RayResult integrate_scalar(const Ray& ray, Diagnostics* diag) const;
  // The batch path for a grey medium without diagnostics: one kernel evaluation per piece for
  // all channels (the channel path's results, bit for bit), for n rays at once into out[0..n).
  // Returns the piece count of PieceSplitter::append.
  long integrate_grey(const Ray* rays, std::size_t n, RayResult* out) const;
  Path path_;
};

}  // namespace rayint
