// psi_table.cpp -- partial pre-integration (Moreland & Angel 2004, "A Fast High Accuracy Volume
// Renderer for Unstructured Data"; VTK's vtkUnstructuredGridPartialPreIntegration).
//
// On a piece where rho and kappa are linear (Williams & Max 1992, Sec. 3.3), with its exit and
// far ends as in model/ray.hpp (Moreland & Angel's "front" and "back"), x_f = rho_exit L,
// x_b = rho_far L (= tau_f D, tau_b D in Moreland & Angel's notation), T = (x_f + x_b)/2 and
// tau(u) = x_f u + (x_b - x_f) u^2/2:
//     I_out = I_in zeta + kappa_far (Psi - zeta) + kappa_exit (1 - Psi),
//     zeta = e^{-T},  Psi = int_0^1 e^{-tau(u)} du  (exact.cpp's e0; 1 - Psi = weight_exit).
// Psi depends on (x_f, x_b) only, and Moreland & Angel tabulate it over
//     gamma = x/(1 + x) in [0, 1]
// which maps [0, inf) onto a bounded square on which Psi is smooth. Everything else (zeta, the
// split at breakpoints, the colours) is computed exactly per piece here; the table is the only
// approximation.
//
// Table: `size` x `size` (default 512, VTK's PSI_TABLE_SIZE; Moreland's thesis used 1024),
// row = gamma_exit, column = gamma_far, grid gamma_i = i/(size - 1) including gamma = 1,
// where x = inf and Psi = 0 (its limit: tau(u) >= x_f u/2 and >= x_b u^2/2 on [0, 1], so
// Psi <= 2/x_f and Psi <= sqrt(pi/(2 x_b))). Entries come
// from exact_piece on a unit-length piece: Psi = weight_far + transmittance and
// 1 - Psi = weight_exit, both stored so that neither is formed by a cancelling subtraction
// (16 bytes per entry: 4 MB at 512, 16 MB at 1024). The table depends only on the size (and
// on VTK's grid for floor), so one instance per size is shared by all cases: built on first
// use, under a mutex, and kept for the life of the process.
//
// Lookups (`lookup`):
//   nearest: the closest grid point in each gamma (error first order in 1/size),
//   linear:  bilinear in (gamma_exit, gamma_far) (second order where Psi is smooth),
//   floor:   VTK's Psi(): grid gamma_i = i/size, i < size, index floor(gamma * size) (first
//            order with a one-sided bias; VTK computes in float, we keep doubles, and clamp
//            the index to size - 1 where gamma rounds to 1).
// Weights from the looked-up values, in the regimes of exact.cpp (kThinDepth = 1):
//   T <= 1: w_exit = clamp(1 - Psi, 0, alpha), w_far = alpha - w_exit, alpha = 1 - zeta
//           from expm1 (w_far >= 0.27 alpha for T <= 1, the minimum at T = 1 with all the
//           density at the exit end, so the subtraction loses < 2 bits);
//   T > 1:  Psi clamped to [zeta, 1] (where the true value lies since 0 <= tau(u) <= T),
//           w_exit = 1 - Psi (> 0.25), w_far = Psi - zeta (> 0.17; the bounds of exact.cpp).
//   Clamping only removes interpolation error that would make a weight negative; it is
//   counted ("psi_clamped"). w_exit + w_far = 1 - zeta always, so a piece of constant kappa
//   (Eq. 5, Eq. 6) is exact whatever the table, and rho = 0 returns the background exactly.
// Error. The intensity of a piece depends on the table only through Psi, with
// dI/dPsi = kappa_far - kappa_exit, so |error| <= |kappa_far - kappa_exit| * |error in Psi|,
// composited like the intensity over the ray (reported as the "error_bound" statistic).
// Where Psi is smooth in gamma (both gammas below ~0.9) the error in Psi is first order in
// h = 1/(size - 1) for nearest/floor and second order for linear. But Psi is not smooth at
// gamma_far = 1 with gamma_exit small (a thick piece whose density falls toward the eye):
// there x_b = gamma/(1 - gamma) -> inf and Psi ~ sqrt(pi/(2 x_b)) ~ sqrt(pi/2) sqrt(1 - gamma_b),
// a square root at the table's edge, and the sup of the error over the square is that of
// interpolating sqrt(t) on the last cell [0, h]:
//     linear  sqrt(pi/2) sqrt(h)/4   (at t = h/4),
//     nearest sqrt(pi/2) sqrt(h/2)   (t just below h/2 read at t = 0),
//     floor   sqrt(pi/2) sqrt(h)     (h = 1/size; t -> 0 read at t = h),
// i.e. order 1/2 in 1/size for every lookup: at size 512 (VTK's) the sup is 1.4e-2 (linear),
// 3.9e-2 (nearest), 5.5e-2 (floor); at 1024, 9.8e-3, 2.8e-2, 3.9e-2. These match the measured
// sup over 3e5 samples of the square to 0.5% for size >= 64; max_error() returns them times
// 1.4, which also covers the pre-asymptotic sizes (worst measured ratio 1.37, linear at size 2).
// Measured (tests/test_tables.cpp [tables], WARN lines):
//   - at grid points equal to exact to rounding: <= 6.7e-16 relative (nearest, linear),
//     2.2e-15 (floor, points nudged 8 ulps so floor() keeps them); asserted <= 1e-14.
//   - off the edge (x = 1e-2..10 at both ends), fitted orders of the Psi error over sizes
//     128..1024: 1.00 nearest, 2.01 linear, 0.99 floor; on the edge 0.50 for all three.
//   - rays against the 50-digit reference (one linear piece per function, 90 channels), fitted
//     orders over sizes 64..1024: 1.00 nearest, 2.00 linear, 1.03 floor; rms relative error of
//     the intensity at 512: 3.0e-4, 5.3e-7, 6.8e-4, at 1024: 1.7e-4, 1.6e-7, 3.0e-4.
//   - within the composited error_bound on 400 random rays from thin to very thick pieces.
//   - cases/: the edge dominates density-decreasing-toward-eye (2.7e-2 at 512 linear, 2.2e-2 at
//     1024); nearest and floor read gamma = 0 (Psi = 1) for pieces much thinner than a grid
//     cell, so such a piece's emission all takes the far colour (cases/thin-pieces: 0.5
//     relative; linear: 8e-4 at 512, first order there since 1 - Psi ~ x_f/3 + x_b/6 is read
//     from the first cell).
//   Build: 0.03 s at 512, 0.13 s at 1024, 0.55 s at 2048 (busy 2-core machine); shared.
// Non-finite never for finite rho L.
#include "rayint/integrators/psi_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/factories.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {

double psi_gamma(double x) {
  // x/(1 + x) overflows to inf/inf for x = inf; 1/(1 + 1/x) does not.
  return x <= 1.0 ? x / (1.0 + x) : 1.0 / (1.0 + 1.0 / x);
}

PsiTable::PsiTable(int size, table::Lookup lookup)
    : size_(size), scale_(lookup == table::Lookup::floor ? size : size - 1) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = static_cast<std::size_t>(size);
  psi_.assign(n * n, 0.0);
  one_minus_psi_.assign(n * n, 1.0);
  std::vector<double> depth(n);  // x = gamma/(1 - gamma); +inf at gamma = 1
  for (int i = 0; i < size; ++i) {
    const double g = gamma(i);
    depth[i] = g < 1.0 ? g / (1.0 - g) : std::numeric_limits<double>::infinity();
  }
  for (std::size_t f = 0; f < n; ++f) {
    for (std::size_t b = 0; b < n; ++b) {
      if (std::isinf(depth[f]) || std::isinf(depth[b])) continue;  // Psi = 0, 1 - Psi = 1
      const PieceOptics o = exact_piece(ChannelPiece{1.0, depth[b], depth[f], 0.0, 0.0});
      psi_[f * n + b] = o.weight_far + o.transmittance;
      one_minus_psi_[f * n + b] = o.weight_exit;
    }
  }
  build_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double PsiTable::gamma(int i) const { return i / scale_; }  // exactly 1 at i = scale_

std::shared_ptr<const PsiTable> PsiTable::shared(int size, table::Lookup lookup) {
  static std::mutex mutex;
  static std::map<std::pair<int, bool>, std::shared_ptr<const PsiTable>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = tables[{size, lookup == table::Lookup::floor}];
  if (!slot) slot = std::make_shared<const PsiTable>(size, lookup);
  return slot;
}

double PsiTable::max_error(table::Lookup lookup) const {
  constexpr double kSqrtHalfPi = 1.2533141373155002512;
  constexpr double kMargin = 1.4;  // pre-asymptotic sizes; see the header comment
  const double h = 1.0 / scale_;
  double c = 1.0;  // floor
  if (lookup == table::Lookup::linear) c = 0.25;
  if (lookup == table::Lookup::nearest) c = std::sqrt(0.5);
  return std::min(1.0, kMargin * kSqrtHalfPi * c * std::sqrt(h));
}

PsiTable::Value PsiTable::lookup(double tau_exit_D, double tau_far_D,
                                 table::Lookup lookup) const {
  const table::GridCoord f = table::locate(psi_gamma(tau_exit_D) * scale_, size_, lookup);
  const table::GridCoord b = table::locate(psi_gamma(tau_far_D) * scale_, size_, lookup);
  return {table::bilerp(psi_.data(), size_, f, b),
          table::bilerp(one_minus_psi_.data(), size_, f, b)};
}

PsiTable::ValueGrad PsiTable::lookup_grad(double tau_exit_D, double tau_far_D,
                                         table::Lookup lookup) const {
  ValueGrad out;
  out.value = this->lookup(tau_exit_D, tau_far_D, lookup);
  if (lookup != table::Lookup::linear) return out;  // piecewise constant
  const double xf = psi_gamma(tau_exit_D) * scale_, xb = psi_gamma(tau_far_D) * scale_;
  const table::GridCoord f = table::locate(xf, size_, lookup);
  const table::GridCoord b = table::locate(xb, size_, lookup);
  const auto n = static_cast<std::size_t>(size_);
  // d coordinate / d depth: scale / (1 + x)^2 inside the grid, 0 where locate() clamped.
  const auto dcoord = [this](double x, double coord) {
    if (!(coord < size_ - 1) || !std::isfinite(x)) return 0.0;
    const double q = 1.0 + x;
    return scale_ / (q * q);
  };
  const double cf = dcoord(tau_exit_D, xf), cb = dcoord(tau_far_D, xb);
  for (int which = 0; which < 2; ++which) {
    const std::vector<double>& v = which == 0 ? psi_ : one_minus_psi_;
    const std::size_t i00 = static_cast<std::size_t>(f.i) * n + static_cast<std::size_t>(b.i);
    const double v00 = v[i00], v01 = v[i00 + 1], v10 = v[i00 + n], v11 = v[i00 + n + 1];
    const double d_row = (1.0 - b.w) * (v10 - v00) + b.w * (v11 - v01);  // per grid unit of gamma_exit
    const double d_col = (1.0 - f.w) * (v01 - v00) + f.w * (v11 - v10);  // per grid unit of gamma_far
    (which == 0 ? out.dpsi_dexit : out.domp_dexit) = d_row * cf;
    (which == 0 ? out.dpsi_dfar : out.domp_dfar) = d_col * cb;
  }
  return out;
}

PsiTableIntegrator::PsiTableIntegrator(const TransferFunctions& tf, int size,
                                       table::Lookup lookup)
    : splitter_(tf),
      lookup_(lookup),
      table_(PsiTable::shared(size, lookup)) {}

RayResult PsiTableIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  RayResult r;
  r.intensity = ray.background;
  r.transmittance = {1.0, 1.0, 1.0};
  long lookups = 0, clamped = 0, transparent = 0;
  const double psi_error = diag ? table_->max_error(lookup_) : 0.0;
  Rgb bound{0.0, 0.0, 0.0};  // composited like the intensity; only kept when diag is set
  for (const auto& seg : ray.segments) {
    const std::vector<Piece>& pieces = splitter_.pieces(seg);
    for (const Piece& piece : pieces) {
      for (int c = 0; c < kChannels; ++c) {
        const double x_exit = piece.rho_exit[c] * piece.length;
        const double x_far = piece.rho_far[c] * piece.length;
        const double T = 0.5 * (x_exit + x_far);
        if (!(T > 0.0)) {  // transparent: nothing absorbed or emitted
          ++transparent;
          continue;
        }
        const PsiTable::Value v = table_->lookup(x_exit, x_far, lookup_);
        ++lookups;
        const double zeta = std::exp(-T);
        double w_exit, w_far;
        if (T <= kThinDepth) {
          const double alpha = -std::expm1(-T);
          w_exit = std::clamp(v.one_minus_psi, 0.0, alpha);
          if (w_exit != v.one_minus_psi) ++clamped;
          w_far = alpha - w_exit;
        } else {
          const double psi = std::clamp(v.psi, zeta, 1.0);
          if (psi != v.psi) ++clamped;
          w_exit = 1.0 - psi;
          w_far = psi - zeta;
        }
        r.intensity[c] = r.intensity[c] * zeta + piece.kappa_exit[c] * w_exit +
                         piece.kappa_far[c] * w_far;
        r.transmittance[c] *= zeta;
        if (diag)
          bound[c] = bound[c] * zeta +
                     std::fabs(piece.kappa_far[c] - piece.kappa_exit[c]) * psi_error;
      }
    }
  }
  if (diag) {
    diag->count("psi_lookup", lookups);
    if (clamped) diag->count("psi_clamped", clamped);
    if (transparent) diag->count("transparent", transparent);
    diag->max_stat("error_bound", std::max({bound[0], bound[1], bound[2]}));
  }
  return r;
}

std::unique_ptr<RayIntegrator> make_psi_table(const MethodSpec& spec,
                                              const TransferFunctions& tf) {
  const int size = spec.integer("size");  // range: registry.cpp (16 B per entry, 1 GiB at 8192)
  const table::Lookup lookup = table::parse_lookup(spec);
  return std::make_unique<PsiTableIntegrator>(tf, size, lookup);
}

}  // namespace rayint
