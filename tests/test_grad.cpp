// Exact gradients of the ray integral (issue 28): integrators/exact_grad.* against the 50-digit
// reference gradient (reference/reference_grad.*), over the case corpus and the stress regimes.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "test_paths.hpp"
#include "rayint/generators/regimes.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/reference/reference_grad.hpp"
#include "rayint/studies/grad_study.hpp"
#include "grad_checks.hpp"
#include "tolerances.hpp"

using namespace rayint;

using test::gradient_error;
using Worst = test::WorstGradientError;

TEST_CASE("exact gradient: forward intensity is exact's, both paths, to rounding", "[grad]") {
  // exact_ray_gradient's forward composites exact_piece's transmittance with exact_batch's
  // emission (integrators/exact_grad.hpp): equal to neither path bit for bit, within
  // GradTolerances::forward_rel of both, relative, over the case corpus.
  double worst_scalar = 0.0, worst_batch = 0.0;
  int rays = 0;
  for (const std::string& file : list_case_files(RAYINT_SOURCE_DIR + "/cases")) {
    if (file.find("/mesh-") != std::string::npos || file.find("gates.json") != std::string::npos) continue;
    const Case cs = read_case_file(file);
    ExactIntegrator scalar(cs.transfer, ExactIntegrator::Path::scalar), batch(cs.transfer);
    for (std::size_t i = 0; i < cs.rays.size(); ++i) {
      const RayGradient g = exact_ray_gradient(cs.transfer, cs.rays[i]);
      const RayResult rs = scalar.integrate(cs.rays[i], nullptr), rb = batch.integrate(cs.rays[i], nullptr);
      INFO(cs.name << " ray " << i);
      for (int c = 0; c < kChannels; ++c) {
        const double es = g.intensity[c] == rs.intensity[c] ? 0.0 : std::fabs(g.intensity[c] - rs.intensity[c]) / std::fabs(rs.intensity[c]);
        const double eb = g.intensity[c] == rb.intensity[c] ? 0.0 : std::fabs(g.intensity[c] - rb.intensity[c]) / std::fabs(rb.intensity[c]);
        CHECK(es <= test::GradTolerances::forward_rel);
        CHECK(eb <= test::GradTolerances::forward_rel);
        worst_scalar = std::max(worst_scalar, es);
        worst_batch = std::max(worst_batch, eb);
      }
      ++rays;
    }
  }
  WARN("gradient's forward intensity over " << rays << " rays: worst relative difference " << worst_scalar
                                            << " from exact:path=scalar, " << worst_batch << " from exact (batch)");
  CHECK(rays > 50);
}

TEST_CASE("exact gradient against the 50-digit reference: piece regimes", "[grad]") {
  std::mt19937_64 rng(28);
  for (const Regime r : all_regimes()) {
    Worst wr;
    for (int i = 0; i < 40; ++i) {
      const RaySample s = sample_ray(r, rng);
      const RayGradient got = exact_ray_gradient(s.transfer, s.ray);
      const ReferenceGradient ref = reference_gradient(s.transfer, s.ray);
      wr.add(got, ref.gradient, regime_name(r) + " #" + std::to_string(i));
    }
    WARN(regime_name(r) << ": worst " << wr.err << " at " << wr.where << " (" << wr.samples << " channels)");
    CHECK(wr.err <= test::GradTolerances::exact_vs_reference_rel);
  }
}

TEST_CASE("exact gradient against the 50-digit reference: ray regimes", "[grad]") {
  std::mt19937_64 rng(2028);
  for (const Regime r : ray_regimes()) {
    Worst wr;
    for (int i = 0; i < 10; ++i) {
      RaySample s = sample_ray(r, rng);
      if (s.ray.segments.size() > 60) s.ray.segments.resize(60);  // long_ray: 60 of its 10^4 segments
      const RayGradient got = exact_ray_gradient(s.transfer, s.ray);
      const ReferenceGradient ref = reference_gradient(s.transfer, s.ray);
      wr.add(got, ref.gradient, regime_name(r) + " #" + std::to_string(i));
    }
    WARN(regime_name(r) << ": worst " << wr.err << " at " << wr.where << " (" << wr.samples << " channels)");
    CHECK(wr.err <= (r == Regime::out_of_range   ? test::GradTolerances::saturated_rel
                     : r == Regime::narrow_pulse ? test::GradTolerances::narrow_pulse_rel
                                                 : test::GradTolerances::exact_vs_reference_rel));
  }
}

TEST_CASE("exact gradient against the 50-digit reference: case corpus", "[grad]") {
  Worst w;
  for (const std::string& file : list_case_files(RAYINT_SOURCE_DIR + "/cases")) {
    if (file.find("/mesh-") != std::string::npos || file.find("gates.json") != std::string::npos) continue;
    const Case cs = read_case_file(file);
    for (std::size_t i = 0; i < cs.rays.size(); ++i) {
      const RayGradient got = exact_ray_gradient(cs.transfer, cs.rays[i]);
      const ReferenceGradient ref = reference_gradient(cs.transfer, cs.rays[i]);
      w.add(got, ref.gradient, cs.name + " ray " + std::to_string(i));
    }
  }
  WARN("corpus: worst " << w.err << " at " << w.where << " (" << w.samples << " ray-channels)");
  CHECK(w.err <= test::GradTolerances::exact_vs_reference_rel);
}

TEST_CASE("exact gradient: kink convention at a constant-scalar segment on a node", "[grad]") {
  // density slopes 4 left of 0.5 and -6 right of it; one segment of constant scalar s.
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = {{0.0, 0.5, 1.0}, {1.0, 3.0, 0.0}};
    tf.color[c] = {{0.0, 1.0}, {0.6, 0.6}};
  }
  const auto at = [&](double s) {
    Ray ray;
    ray.segments = {{0.7, s, s}};
    return ray;
  };
  const RayGradient on = exact_ray_gradient(tf, at(0.5));
  const RayGradient right = exact_ray_gradient(tf, at(0.5 + 1e-9));
  const RayGradient left = exact_ray_gradient(tf, at(0.5 - 1e-9));
  // The documented side: the interval to the right of the node.
  for (int c = 0; c < kChannels; ++c) {
    CHECK(std::fabs(on.scalar_far[0][c] - right.scalar_far[0][c]) <= 1e-7 * std::fabs(right.scalar_far[0][c]));
    CHECK(std::fabs(on.density[c][1].position - right.density[c][1].position) <=
          1e-7 * std::fabs(right.density[c][1].position));
    // ... and not the left one: the slopes differ in sign.
    CHECK(on.scalar_far[0][c] * left.scalar_far[0][c] < 0.0);  // colour constant: only rho moves
  }
  // The reference takes the same side by its one-sided stencils.
  const ReferenceGradient ref = reference_gradient(tf, at(0.5));
  for (int c = 0; c < kChannels; ++c) CHECK(gradient_error(on, ref.gradient, c, nullptr) <= 1e-15);
}


TEST_CASE("riemann, nerf, pl_nerf, psi_table gradients: the derivative of each renderer's own sum", "[grad]") {
  // Kinks inside segments, no sample within 1e-6 of a node (sample positions are k/n, (k+1/2)/n
  // of scalar spans with irrational-looking ends).
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{0.0, 0.43, 1.0}, {0.3, 2.1, 0.7}}, PiecewiseLinear{{0.0, 1.0}, {0.5, 1.5}},
                PiecewiseLinear{{0.1, 0.61, 0.9}, {1.0, 0.2, 2.5}}};
  tf.color = {PiecewiseLinear{{0.0, 1.0}, {0.9, 0.3}}, PiecewiseLinear{{0.0, 0.57, 1.0}, {0.4, 0.8, 0.5}},
              PiecewiseLinear{{0.0, 1.0}, {0.2, 0.7}}};
  const Ray ray = test::three_segment_ray();
  // psi_table: the derivative of the bilinear table (no lookup here lies within a difference
  // step of a grid line). lookup=nearest is piecewise constant in Psi and a step of 1e-6 straddles
  // one of its jumps here (node 0 of density r: differences 5.9 at h = 1e-6, -0.0497294222 at
  // h = 1e-7, the gradient -0.0497294222), so it is not compared with this helper.
  for (const char* spec : {"riemann:n=16", "nerf:n=16", "nerf:n=16:at=near", "pl_nerf:n=16", "pl_nerf:n=16:color=near",
                           "psi_table:size=64", "psi_table:size=512"}) {
    const RayGradient got = method_gradient(parse_method_spec(spec), tf, ray);
    // Central differences in double of the renderer's own intensity, step 1e-6: truncation
    // ~1e-12 and rounding ~1e-10 relative.
    const RayGradient fd = test::method_finite_difference(spec, tf, ray, 1e-6);
    for (int c = 0; c < kChannels; ++c) {
      std::string where;
      const double err = gradient_error(got, fd, c, &where);
      INFO(spec << " channel " << c << " worst at " << where);
      CHECK(err <= 1e-8);
      // ... and the intensity is the renderer's (up to the summation order's rounding).
      const double I = make_integrator(parse_method_spec(spec), tf)->integrate(ray, nullptr).intensity[c];
      CHECK(std::fabs(got.intensity[c] - I) <= 1e-14 * std::fabs(I));
    }
  }
}

TEST_CASE("exact gradient against the 50-digit reference: every moment method near its thresholds", "[grad]") {
  // One-piece rays (piece_as_ray, length 1) by (A, B) = (a, (b - a)/2) in each region of
  // exact_grad.cpp, concentrated at its thresholds.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const char* names[] = {"erfcx identity (z0 in [0.3, 2])", "erfcx fraction (z0 in [1, 11])",
                         "erfcx fraction (z0 in [10, 4e3])", "dawson exit series (T <= 50)",
                         "dawson Laplace series (T > 50)", "q2 series near 2^-26",
                         "dawson rho_far = 0, T in [40, 50]"};
  for (int cls = 0; cls < 7; ++cls) {
    Worst w;
    for (int i = 0; i < 40; ++i) {
      double A = 0.0, B = 0.0;
      const double u = U(rng);
      if (cls == 0) {
        const double z0 = 0.3 + 1.7 * u;
        B = std::pow(10.0, -2.0 + 5.0 * U(rng));
        A = 2.0 * z0 * std::sqrt(B);
      } else if (cls == 1) {
        const double z0 = 1.0 + 10.0 * u * u;
        B = std::pow(10.0, -3.0 + 5.0 * U(rng));
        A = 2.0 * z0 * std::sqrt(B);
      } else if (cls == 2) {
        const double z0 = std::pow(10.0, 1.0 + 2.6 * u);
        A = 1.0 + 100.0 * U(rng);
        B = (A / (2.0 * z0)) * (A / (2.0 * z0));
      } else if (cls == 3 || cls == 4) {
        const double T = cls == 3 ? 1.0 + 49.0 * u : 50.0 + 100.0 * u;
        const double frac = cls == 3 ? U(rng) : std::pow(10.0, -7.0 + 7.0 * U(rng));
        A = 2.0 * T / (2.0 - frac);
        B = 0.5 * (A * (1.0 - frac) - A);
      } else if (cls == 5) {
        A = 1.0 + 100.0 * u;
        B = std::pow(10.0, -9.0 + 3.0 * U(rng)) * (U(rng) < 0.5 ? -1.0 : 1.0) * A * A;
      } else {
        const double T = 40.0 + 10.0 * u;
        A = 2.0 * T;
        B = -T;
      }
      const double b = std::max(0.0, A + 2.0 * B);
      RegimeSample s;
      s.piece = {1.0, b, A, 10.0 * U(rng), 10.0 * U(rng)};
      s.incoming = U(rng);
      const RaySample rs = piece_as_ray(s);
      w.add(exact_ray_gradient(rs.transfer, rs.ray), reference_gradient(rs.transfer, rs.ray).gradient,
            std::string(names[cls]) + " #" + std::to_string(i) + " (" +
                moment_method_name(exact_piece_grad(s.piece).method) + ")");
    }
    WARN(names[cls] << ": worst " << w.err << " at " << w.where);
    CHECK(w.err <= test::GradTolerances::exact_vs_reference_rel);
  }
}

TEST_CASE("exact gradient: a grey channel's piece from another channel's depth is the full computation, bit for bit",
          "[grad]") {
  // exact_piece_grad(p, dkappa, same_depth) reuses the moments and weights of a piece with the
  // same length and densities (the chain's grey medium); it must return what the full
  // computation returns for every field, in every regime (so in every moment method).
  std::mt19937_64 rng(2828);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int pieces = 0;
  for (const Regime r : all_regimes())
    for (int i = 0; i < 40; ++i) {
      const ChannelPiece first = sample_piece(r, rng).piece;
      ChannelPiece other = first;
      other.kappa_far = i % 5 == 0 ? 0.0 : 3.0 * U(rng);
      other.kappa_exit = i % 7 == 0 ? 0.0 : 3.0 * U(rng);
      const double dkappa = other.kappa_far - other.kappa_exit;
      const PieceOpticsGrad full = exact_piece_grad(other, dkappa);
      const PieceOpticsGrad reused = exact_piece_grad(other, dkappa, exact_piece_grad(first, first.kappa_far - first.kappa_exit));
      INFO(regime_name(r) << " #" << i << " (" << moment_method_name(full.method) << ")");
      CHECK(reused.optics.emission == full.optics.emission);
      CHECK(reused.optics.transmittance == full.optics.transmittance);
      CHECK(reused.optics.weight_exit == full.optics.weight_exit);
      CHECK(reused.optics.weight_far == full.optics.weight_far);
      CHECK(reused.de_length == full.de_length);
      CHECK(reused.de_rho_far == full.de_rho_far);
      CHECK(reused.de_rho_exit == full.de_rho_exit);
      CHECK(reused.de_kappa_far == full.de_kappa_far);
      CHECK(reused.de_kappa_exit == full.de_kappa_exit);
      CHECK(reused.dt_length == full.dt_length);
      CHECK(reused.dt_rho_far == full.dt_rho_far);
      CHECK(reused.dt_rho_exit == full.dt_rho_exit);
      ++pieces;
    }
  CHECK(pieces >= 40 * 10);
}

TEST_CASE("exact gradient: the segment blocks alone (GradientBlocks::segments) are the full gradient's, bit for bit",
          "[grad]") {
  // Over the case corpus (grey and coloured densities, breakpoints inside segments, constant
  // segments on nodes): intensity, background, length and end-scalar entries equal, the node
  // blocks left empty; and the intensity is exact:path=scalar's (an independent forward) to
  // GradTolerances::forward_rel.
  int rays = 0;
  for (const std::string& file : list_case_files(RAYINT_SOURCE_DIR + "/cases")) {
    if (file.find("/mesh-") != std::string::npos || file.find("gates.json") != std::string::npos) continue;
    const Case cs = read_case_file(file);
    ExactIntegrator scalar(cs.transfer, ExactIntegrator::Path::scalar);
    for (std::size_t i = 0; i < cs.rays.size(); ++i) {
      const RayGradient all = exact_ray_gradient(cs.transfer, cs.rays[i]);
      RayGradient seg;
      exact_ray_gradient(cs.transfer, cs.rays[i], seg, GradientBlocks::segments);
      INFO(cs.name << " ray " << i);
      const RayResult fwd = scalar.integrate(cs.rays[i], nullptr);
      for (int c = 0; c < kChannels; ++c) {
        CHECK(std::fabs(all.intensity[c] - fwd.intensity[c]) <=
              test::GradTolerances::forward_rel * std::fabs(fwd.intensity[c]));
        CHECK(seg.intensity[c] == all.intensity[c]);
        CHECK(seg.background[c] == all.background[c]);
        CHECK(seg.density[c].empty());
        CHECK(seg.color[c].empty());
        for (std::size_t j = 0; j < all.length.size(); ++j) {
          CHECK(seg.length[j][c] == all.length[j][c]);
          CHECK(seg.scalar_far[j][c] == all.scalar_far[j][c]);
          CHECK(seg.scalar_exit[j][c] == all.scalar_exit[j][c]);
        }
      }
      CHECK(seg.undefined == all.undefined);
      ++rays;
    }
  }
  CHECK(rays > 50);
}
