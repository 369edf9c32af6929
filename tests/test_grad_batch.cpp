// exact_pieces_grad (the batched piece derivatives behind exact_ray_gradient) against the scalar
// exact_piece_grad, piece by piece, in every regime and near every moment method's thresholds, on
// every SIMD target this CPU runs: every optic and derivative (PieceDerivatives) within
// GradTolerances::batch_vs_scalar_rel of the scalar one (relative to the largest entry of its
// kind: the emission derivatives, the transmittance derivatives).
// The ray gradient it feeds is tested against the 50-digit reference in tests/test_grad.cpp.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "simd_targets.hpp"
#include "tolerances.hpp"

using namespace rayint;

namespace {

// Pieces of every piece regime, then pieces by (A, B) at the moment methods' thresholds (as the
// reference test "every moment method near its thresholds" draws them), then a zero-length and a
// zero-density piece.
std::vector<ChannelPiece> pieces_of_every_regime(std::mt19937_64& rng) {
  std::vector<ChannelPiece> out;
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (const Regime r : all_regimes())
    for (int i = 0; i < 200; ++i) out.push_back(sample_piece(r, rng).piece);
  for (int cls = 0; cls < 7; ++cls)
    for (int i = 0; i < 200; ++i) {
      double A = 0.0, B = 0.0;
      const double u = U(rng);
      if (cls == 0) {  // erfcx identity, z0 in [0.3, 2]
        const double z0 = 0.3 + 1.7 * u;
        B = std::pow(10.0, -2.0 + 5.0 * U(rng));
        A = 2.0 * z0 * std::sqrt(B);
      } else if (cls == 1) {  // erfcx fraction, z0 in [1, 11]
        const double z0 = 1.0 + 10.0 * u * u;
        B = std::pow(10.0, -3.0 + 5.0 * U(rng));
        A = 2.0 * z0 * std::sqrt(B);
      } else if (cls == 2) {  // erfcx fraction, z0 in [10, 4e3]
        const double z0 = std::pow(10.0, 1.0 + 2.6 * u);
        A = 1.0 + 100.0 * U(rng);
        B = (A / (2.0 * z0)) * (A / (2.0 * z0));
      } else if (cls == 3 || cls == 4) {  // dawson exit series (T <= 50), Laplace series (T > 50)
        const double T = cls == 3 ? 1.0 + 49.0 * u : 50.0 + 100.0 * u;
        const double frac = cls == 3 ? U(rng) : std::pow(10.0, -7.0 + 7.0 * U(rng));
        A = 2.0 * T / (2.0 - frac);
        B = 0.5 * (A * (1.0 - frac) - A);
      } else if (cls == 5) {  // q2 series near 2^-26
        A = 1.0 + 100.0 * u;
        B = std::pow(10.0, -9.0 + 3.0 * U(rng)) * (U(rng) < 0.5 ? -1.0 : 1.0) * A * A;
      } else {  // thin series near T = 1
        const double T = 0.9 + 0.2 * u;
        A = 2.0 * T * U(rng);
        B = T - A;
      }
      out.push_back({1.0, std::max(0.0, A + 2.0 * B), A, 10.0 * U(rng), 10.0 * U(rng)});
    }
  out.push_back({0.0, 1.0, 2.0, 0.5, 0.25});
  out.push_back({1.5, 0.0, 0.0, 0.5, 0.25});
  return out;
}

double rel(double got, double want, double scale) {
  if (got == want) return 0.0;
  return std::fabs(got - want) / scale;  // NaN if either is NaN: fails the check below
}

}  // namespace

TEST_CASE("exact_pieces_grad against exact_piece_grad in every regime, on every SIMD target", "[grad][exact_batch]") {
  std::mt19937_64 rng(2829);
  const std::vector<ChannelPiece> pieces = pieces_of_every_regime(rng);
  std::vector<double> dkappa(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) dkappa[i] = pieces[i].kappa_far - pieces[i].kappa_exit;
  test::for_each_simd_target([&] {
    for (const int stride : {1, kChannels}) {  // stride 3: every third piece's depth reused (grey)
      std::vector<ChannelPiece> in = pieces;
      if (stride > 1)
        for (std::size_t i = 0; i < in.size(); ++i) {
          const std::size_t first = i - i % kChannels;
          in[i].length = in[first].length;
          in[i].rho_far = in[first].rho_far;
          in[i].rho_exit = in[first].rho_exit;
        }
      std::vector<PieceDerivatives> got(in.size());
      exact_pieces_grad(in.data(), dkappa.data(), in.size(), got.data(), stride);
      double worst = 0.0;
      std::string where;
      for (std::size_t i = 0; i < in.size(); ++i) {
        const PieceOpticsGrad full = exact_piece_grad(in[i], dkappa[i]);
        const PieceDerivatives want = derivatives_of(full);
        const PieceDerivatives& g = got[i];
        INFO("target " << exact_batch_target() << " stride " << stride << " piece " << i << " (L "
                       << in[i].length << ", rho_far " << in[i].rho_far << ", rho_exit " << in[i].rho_exit
                       << ", method " << moment_method_name(full.method) << ")");
        const double de_scale =
            std::max({std::fabs(want.de_length), std::fabs(want.de_rho_far), std::fabs(want.de_rho_exit),
                      std::fabs(want.de_kappa_far), std::fabs(want.de_kappa_exit), std::fabs(want.emission),
                      1e-300});
        const double dt_scale = std::max({std::fabs(want.dt_length), std::fabs(want.dt_rho),
                                          std::fabs(want.transmittance), 1e-300});
        const std::pair<const char*, double> errs[] = {
            {"emission", rel(g.emission, want.emission, de_scale)},
            {"transmittance", rel(g.transmittance, want.transmittance, dt_scale)},
            {"de_length", rel(g.de_length, want.de_length, de_scale)},
            {"de_rho_far", rel(g.de_rho_far, want.de_rho_far, de_scale)},
            {"de_rho_exit", rel(g.de_rho_exit, want.de_rho_exit, de_scale)},
            {"de_kappa_far (weight_far)", rel(g.de_kappa_far, want.de_kappa_far, de_scale)},
            {"de_kappa_exit (weight_exit)", rel(g.de_kappa_exit, want.de_kappa_exit, de_scale)},
            {"dt_length", rel(g.dt_length, want.dt_length, dt_scale)},
            {"dt_rho", rel(g.dt_rho, want.dt_rho, dt_scale)},
        };
        for (const auto& [name, err] : errs) {
          INFO(name << ": batch vs scalar " << err);
          CHECK(err <= test::GradTolerances::batch_vs_scalar_rel);
          if (err > worst) {
            worst = err;
            where = std::string(name) + " of piece " + std::to_string(i) + " (" + moment_method_name(full.method) + ")";
          }
        }
      }
      WARN("exact_pieces_grad (" << exact_batch_target() << ", stride " << stride << ") vs exact_piece_grad over "
                                 << in.size() << " pieces: worst " << worst << " at " << where);
    }
  });
}
