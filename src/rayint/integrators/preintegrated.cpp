// preintegrated.cpp -- pre-integrated transfer functions (Engel, Kraus & Ertl 2001): the ray
// integral of Williams & Max (1992, Eq. 4) over a step of length l whose scalar runs linearly
// from s_far to s_exit, read from a table over (s_far, s_exit) built once per case with the
// exact kernel; with dims=3 (Roettger, Kraus & Ertl 2000) the length is a third table axis.
//
// Table (built in the constructor; its cost is reported by build_seconds(), not per ray).
//   Scalar axes: `size` points on [s_lo, s_hi] = [first, last breakpoint of the six transfer
//   functions] (beyond it every function is constant). Row = s_far, column = s_exit.
//   Per entry and channel, with the step's pieces found by append_pieces (split at every
//   breakpoint) on a step of unit length:
//     rate = (1/l) * optical depth of the step = mean of rho along the scalar path (exact; it
//            does not depend on l, so one array serves every length),
//     q(L) = E(L) / (L phi(rate L)),  phi(t) = (1 - e^{-t})/t (step_weight, core/math.hpp),
//            E(L) = emission of a step of length L, composited far -> near with exact_piece;
//            q(0) = mean of kappa*rho along the path (the L -> 0 limit, from the per-piece
//            closed form of the integral).
//   q is "emission per unit length, corrected for self-absorption": for constant kappa,
//   q = kappa * rate exactly, whatever the length. dims=2 stores one plane, L = D (`step`);
//   dims=3 stores `lengths` planes L_k = k max_length/(lengths - 1), k = 0 .. lengths - 1.
//   Memory: size^2 (3 + 3 planes) doubles = 6 size^2 doubles for dims=2 (3 MB at size 256).
//
// Lookup of a step (s_far, s_exit, l): rate and q are read with `lookup` = nearest or linear
// (bilinear in the scalars; dims=3 also linear in L between the two planes around l, nearest
// plane otherwise), then
//     tau = rate * l,  transmittance = e^{-tau},  emission = q * l * phi(tau),
// so transmittance and emission always satisfy the emission <= kappa_max (1 - transmittance)
// bound of Eq. 5, and every value is finite and >= 0.
//   - For a step of length l != L_k this is the renderer's "opacity correction"
//     alpha' = 1 - (1 - alpha)^(l/L_k), extended to the colour: exact for the transmittance,
//     and exact for the emission when kappa is constant along the step.
//
// How a ray is cut.
//   dims=2: each segment is cut into steps of length D from its far end; the last step is
//     l = L - (n-1) D <= D and uses the length correction above (renderers do the same when a
//     sample spacing changes). A remainder below 1e-9 D (L/D an integer up to rounding) is
//     merged into the previous step. Default D = 2^-6: a binary fraction so that lengths such
//     as 0.25, 0.5, 1, 2 are whole numbers of steps; the per-ray cost is L/D lookups.
//   dims=3: each segment is one lookup (s_far, s_exit, L); a segment longer than max_length
//     (default 4, longer than most segments of cases/) is cut into ceil(L/max_length) equal
//     parts. Default lengths = min(size, 32): memory grows with size^2 * lengths.
//   A ray needing more than kPreintegratedMaxLookupsPerRay = 2^22 lookups (about 0.1 s) is
//   refused with an exception instead of running for minutes (the budget exists for cases
//   like L = 1e9 at D = 2^-6); pass a larger step/max_length for such rays. A table over
//   kPreintegratedMaxTableBytes = 1 GiB is refused at build (dims=2 reaches it near size 4700).
//
// Error sources, each measured in tests/test_tables.cpp ([tables]; figures from its WARN lines):
//   - interpolation of rate and q between scalar grid points, h = (s_hi - s_lo)/(size - 1):
//     first order for nearest, second order for linear where the transfer functions are
//     smooth (fitted orders against the 50-digit reference, sizes 32..512: 1.14 and 2.04
//     (dims=2), 1.10 and 2.09 (dims=3, sizes 16..64 with lengths = size)). rms relative error
//     of the ray intensity at size 256: 1.4e-4 nearest, 2.9e-6 linear. Where a breakpoint falls
//     inside a grid cell q has a kink and linear is first order in that cell only (over many
//     rays the rms still fell as 1/size^2 in an exploratory run with two interior breakpoints;
//     not asserted). rate is exact under
//     linear lookup when rho is linear between the smallest and largest of the four grid
//     scalars around the lookup, so then the transmittance is exact too.
//   - dims=3: interpolation of q in L, second order in max_length/(lengths - 1) while a
//     plane spacing holds little optical depth; where rho is so high that a segment saturates
//     within one spacing, q is read between the thin limit (plane 0) and saturated planes
//     (cases/very-thick-pieces, rho up to 1.5e6: 0.28 relative at size 256, 32 planes).
//   - the length correction of a short last step (dims=2) when kappa varies along it: one step
//     of r D between grid scalars (D = 0.25, tau ~ 0.3, smooth case) is exact at r = 1 and off
//     by 1.9e-3, 9.6e-3, 1.8e-2 relative at r = 0.9, 0.5, 0.1. It dominates the error of
//     cases/ with segments shorter than D (thin-pieces 1.2e-3, steep-slopes 1.6e-2 at size 256).
//   - scalars outside [s_lo, s_hi] are clamped to the table, as a renderer clamps texture
//     coordinates: exact for a step entirely outside the range, wrong for a step that crosses
//     into it (its scalar path is bent; counted as "scalar_clamped"). dims=3 looks up whole
//     segments, so one crossing segment carries the whole error (cases/scalar-outside-range:
//     0.95 relative for dims=3, 9e-5 for dims=2, whose steps outside are exact).
//   - features narrower than a grid cell (cases/narrow-pulse, 1e-12 wide): a step whose scalar
//     path lies inside the pulse reads corners that average the pulse over a whole cell;
//     relative error up to 1 at any practical size. This is the method's known limit.
// Analytic limits: constant kappa and rho (Eq. 6) exact for every size, lookup, dims, any
// length (measured <= 2.9e-14 relative, rounding over ~800 steps); constant kappa with rho
// linear in the scalar (Eq. 5) exact under linear lookup (<= 3.6e-15); rho = 0 returns the
// background bit for bit.
// Cost per lookup: two bilinear reads, exp and expm1 per channel (~20 ns: 475 lookups in
// 9 us on cases/smooth-convergence). Build cost (wall clock, busy 2-core machine, rows shared over the hardware threads): dims=2
// size 256: 0.03-0.1 s, 512: 0.15-0.25 s, 1024: 1.0 s, 2048: 5.5 s (201 MB); dims=3 size 64 with
// 32 planes 0.15 s, size 256 with 32 planes 2.2 s (52 MB).
#include "rayint/integrators/preintegrated.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/core/math.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/factories.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
double preintegrated_step_count(double length, double step) {
  const double ratio = length / step;
  double n = std::ceil(ratio);
  if (n >= 2.0 && ratio - (n - 1.0) <= 1e-9) n -= 1.0;
  return std::max(n, 1.0);
}

PreintegratedOptions preintegrated_options(const MethodSpec& spec) {
  PreintegratedOptions o;
  // Types and ranges: the method table (registry.cpp); here what combines parameters.
  o.size = spec.integer("size");
  o.lookup = table::parse_lookup(spec);
  o.dims = spec.integer("dims");
  const auto reject = [&](const char* key, const char* why) {
    if (spec.params.count(key))
      throw std::invalid_argument("method " + spec.name + ": " + key + " " + why);
  };
  if (o.dims == 2) {
    reject("max_length", "applies to dims=3 only");
    reject("lengths", "applies to dims=3 only");
    o.step = spec.number("step");
  } else {
    reject("step", "applies to dims=2 only (dims=3 looks each segment up whole)");
    o.max_length = spec.number("max_length");
    o.lengths = spec.has("lengths") ? spec.integer("lengths") : std::min(o.size, 32);
  }
  if (preintegrated_table_bytes(o) > kPreintegratedMaxTableBytes)
    throw std::invalid_argument(
        "method " + spec.name + ": a table of " +
        std::to_string(static_cast<long long>(preintegrated_table_bytes(o) / (1 << 20))) +
        " MiB exceeds the 1 GiB limit; lower size or lengths");
  return o;
}

PreintegratedIntegrator::PreintegratedIntegrator(const TransferFunctions& tf,
                                                 const PreintegratedOptions& options)
    : opt_(options) {
  const auto start = std::chrono::steady_clock::now();
  if (opt_.dims == 2) {
    plane_length_ = {opt_.step};
  } else {
    const int n = opt_.lengths;
    for (int k = 0; k < n; ++k) plane_length_.push_back(opt_.max_length * k / (n - 1));
    plane_length_.back() = opt_.max_length;
    inv_dL_ = (n - 1) / opt_.max_length;
  }
  if (table_bytes() > kPreintegratedMaxTableBytes)
    throw std::invalid_argument("preintegrated: a table of " + std::to_string(table_bytes()) +
                                " bytes exceeds the 1 GiB limit; lower size or lengths");

  const std::vector<double> breakpoints = tf.breakpoints();
  s_lo_ = breakpoints.front();
  s_hi_ = breakpoints.back();
  if (!(s_hi_ > s_lo_)) s_hi_ = s_lo_ + 1.0;  // one breakpoint: every function is constant
  const int n = opt_.size;
  inv_ds_ = (n - 1) / (s_hi_ - s_lo_);
  const auto grid_scalar = [this](int i) { return this->grid_scalar(i); };

  const std::size_t entries = static_cast<std::size_t>(n) * n;
  for (auto& r : rate_) r.assign(entries, 0.0);
  q_.assign(plane_length_.size() * kChannels, std::vector<double>(entries, 0.0));

  // Rows are independent; they are shared out over the hardware threads by parallel_for (each
  // entry is written by exactly one worker, so the table does not depend on the thread count).
  const auto build_row = [&](int i, std::vector<Piece>& pieces) {
    for (int j = 0; j < n; ++j) {
      const std::size_t e = static_cast<std::size_t>(i) * n + j;
      pieces.clear();
      append_pieces(tf, Segment{1.0, grid_scalar(i), grid_scalar(j)}, breakpoints, pieces);
      for (int c = 0; c < kChannels; ++c) {
        double rate = 0.0, thin = 0.0;
        for (const Piece& p : pieces) {
          const double rf = p.rho_far[c], re = p.rho_exit[c];
          const double kf = p.kappa_far[c], ke = p.kappa_exit[c];
          rate += p.length * 0.5 * (rf + re);
          // int_0^1 kappa rho du with both linear in u.
          thin += p.length * (2.0 * kf * rf + kf * re + ke * rf + 2.0 * ke * re) / 6.0;
        }
        rate_[c][e] = rate;
        for (std::size_t k = 0; k < plane_length_.size(); ++k) {
          const double L = plane_length_[k];
          double q = thin;
          if (L > 0.0) {
            double emission = 0.0;
            for (const Piece& p : pieces) {
              ChannelPiece cp = p.channel(c);
              cp.length *= L;
              const PieceOptics o = exact_piece(cp);
              emission = emission * o.transmittance + o.emission;
            }
            q = emission / (L * step_weight(rate * L));
          }
          q_[k * kChannels + c][e] = q;
        }
      }
    }
  };
  const unsigned threads = std::max(
      1u, std::min(resolve_threads(0), static_cast<unsigned>(entries * plane_length_.size() / 16384)));
  std::vector<std::vector<Piece>> pieces(parallel_workers(n, threads));  // scratch per worker
  parallel_for(n, threads, [&](long long i, unsigned w) { build_row(static_cast<int>(i), pieces[w]); });
  build_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double preintegrated_table_bytes(const PreintegratedOptions& o) {
  const double entries = static_cast<double>(o.size) * o.size;
  const double planes = o.dims == 2 ? 1.0 : o.lengths;
  return entries * kChannels * (1.0 + planes) * sizeof(double);
}

double PreintegratedIntegrator::grid_scalar(int i) const {
  const int n = opt_.size;
  return i == n - 1 ? s_hi_ : s_lo_ + (s_hi_ - s_lo_) * i / (n - 1);
}

double PreintegratedIntegrator::table_bytes() const { return preintegrated_table_bytes(opt_); }

PreintegratedIntegrator::StepOptics PreintegratedIntegrator::lookup(double s_far, double s_exit,
                                                                    double length) const {
  const int n = opt_.size;
  const table::GridCoord row = table::locate((s_far - s_lo_) * inv_ds_, n, opt_.lookup);
  const table::GridCoord col = table::locate((s_exit - s_lo_) * inv_ds_, n, opt_.lookup);
  table::GridCoord plane;  // plane 0 for dims = 2
  if (opt_.dims == 3)
    plane = table::locate(length * inv_dL_, static_cast<int>(plane_length_.size()), opt_.lookup);
  StepOptics out;
  for (int c = 0; c < kChannels; ++c) {
    const double rate = table::bilerp(rate_[c].data(), n, row, col);
    const std::size_t k = static_cast<std::size_t>(plane.i) * kChannels + c;
    double q = table::bilerp(q_[k].data(), n, row, col);
    if (plane.w > 0.0)
      q = (1.0 - plane.w) * q + plane.w * table::bilerp(q_[k + kChannels].data(), n, row, col);
    const double tau = rate * length;
    out.depth[c] = tau;
    out.transmittance[c] = std::exp(-tau);
    out.emission[c] = q * length * step_weight(tau);
  }
  return out;
}

double PreintegratedIntegrator::count_lookups(const Ray& ray) const {
  const double cut = opt_.dims == 2 ? opt_.step : opt_.max_length;
  double lookups = 0.0;
  for (const auto& seg : ray.segments)
    if (seg.length > 0.0) lookups += preintegrated_step_count(seg.length, cut);
  if (lookups > static_cast<double>(kPreintegratedMaxLookupsPerRay))
    throw std::runtime_error("preintegrated: the ray needs " + std::to_string(lookups) +
                             " table lookups, over the budget of 2^22; use a larger " +
                             (opt_.dims == 2 ? "step" : "max_length"));
  return lookups;
}

RayResult PreintegratedIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  const double lookups = count_lookups(ray);
  // Emission is composited step by step; the background term uses the total optical depth,
  // summed with Neumaier's compensation (relative error ~ 1 ulp of the total, against
  // ~ n ulps for a product of n step transmittances), and a product of many factors that has
  // underflowed into subnormals cannot stick at a nonzero value (e.g. 1.6e-322 * 0.98 rounds
  // back to 1.6e-322) where the true transmittance is e^{-1000}.
  Rgb emission{0.0, 0.0, 0.0}, depth{0.0, 0.0, 0.0}, depth_carry{0.0, 0.0, 0.0};
  long clamped = 0, corrected = 0, split = 0;
  const auto outside = [&](double s) { return s < s_lo_ || s > s_hi_; };
  std::size_t last_split = ray.segments.size();
  for_each_step(ray, [&](const Cut& cut) {
    const StepOptics o = lookup(cut.s0, cut.s1, cut.l);
    for (int c = 0; c < kChannels; ++c) {
      emission[c] = emission[c] * o.transmittance[c] + o.emission[c];
      const double sum = depth[c] + o.depth[c];
      depth_carry[c] += std::fabs(depth[c]) >= std::fabs(o.depth[c])
                            ? (depth[c] - sum) + o.depth[c]
                            : (o.depth[c] - sum) + depth[c];
      depth[c] = sum;
    }
    if (outside(cut.s0) || outside(cut.s1)) ++clamped;
    if (opt_.dims == 2 && std::fabs(cut.l - opt_.step) > 1e-9 * opt_.step) ++corrected;
    // dims = 3: a segment cut into more than one part (its first part is not its whole length).
    if (opt_.dims == 3 && cut.segment != last_split && cut.l < ray.segments[cut.segment].length) {
      ++split;
      last_split = cut.segment;
    }
  });
  RayResult r;
  for (int c = 0; c < kChannels; ++c) {
    r.transmittance[c] = std::exp(-(depth[c] + depth_carry[c]));
    r.intensity[c] = ray.background[c] * r.transmittance[c] + emission[c];
  }
  if (diag) {
    diag->count("table_lookup", static_cast<long>(lookups));
    if (clamped) diag->count("scalar_clamped", clamped);
    if (corrected) diag->count("length_corrected", corrected);
    if (split) diag->count("long_segment_split", split);
  }
  return r;
}

std::unique_ptr<RayIntegrator> make_preintegrated(const MethodSpec& spec,
                                                  const TransferFunctions& tf) {
  return std::make_unique<PreintegratedIntegrator>(tf, preintegrated_options(spec));
}

}  // namespace rayint
