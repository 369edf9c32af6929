// The batched exact path (integrators/exact_batch.*) against the 50-digit reference, regime by
// regime, and against the scalar exact_piece: same branch, same series terms, same gate.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/reference.hpp"
#include "simd_targets.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using namespace rayint::test;

namespace {

struct Batch {
  std::vector<double> length, rho_far, rho_exit, kappa_far, kappa_exit;
  std::vector<double> transmittance, emission;
  std::vector<ExactBranch> branch;
  std::vector<std::int32_t> terms;
  std::vector<unsigned char> converged;

  void add(const ChannelPiece& p) {
    length.push_back(p.length);
    rho_far.push_back(p.rho_far);
    rho_exit.push_back(p.rho_exit);
    kappa_far.push_back(p.kappa_far);
    kappa_exit.push_back(p.kappa_exit);
  }
  void run() {
    const std::size_t n = length.size();
    transmittance.assign(n, -1.0);
    emission.assign(n, -1.0);
    branch.assign(n, ExactBranch::transparent);
    terms.assign(n, -1);
    converged.assign(n, 2);
    exact_batch({length.data(), rho_far.data(), rho_exit.data(), kappa_far.data(), kappa_exit.data(), n},
                {transmittance.data(), emission.data(), branch.data(), terms.data(), converged.data()});
  }
};

bool within(double x, const ExtendedValue& ref, double rel) {
  if (!std::isfinite(x)) return false;
  if (relative_error(x, ref) <= rel) return true;
  return std::fabs(ref.hi) < 1e-290 && absolute_error(x, ref) <= Tolerances::exact_abs_underflow;
}

}  // namespace

namespace {

void check_all_regimes_in_one_batch() {
  std::mt19937_64 rng(7);
  std::vector<std::pair<Regime, RegimeSample>> drawn;
  for (const Regime regime : all_regimes())
    for (int i = 0; i < 150; ++i) drawn.emplace_back(regime, sample_piece(regime, rng));
  std::shuffle(drawn.begin(), drawn.end(), std::mt19937_64(3));  // branches interleaved
  std::vector<RegimeSample> samples;
  for (const auto& d : drawn) samples.push_back(d.second);
  Batch batch;
  for (const auto& s : samples) batch.add(s.piece);
  batch.run();
  std::vector<double> ulps_batch, ulps_scalar;
  std::map<std::string, long> branches;
  double worst = 0.0, worst_vs_scalar = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const RegimeSample& s = samples[i];
    const PieceOptics o = exact_piece(s.piece);
    const ReferencePiece ref = reference_piece(s.piece, s.incoming);
    const double intensity = s.incoming * batch.transmittance[i] + batch.emission[i];
    branches[branch_name(batch.branch[i])]++;
    INFO("regime " << regime_name(drawn[i].first) << " branch " << branch_name(batch.branch[i]) << " L "
                   << s.piece.length << " rho_exit " << s.piece.rho_exit << " rho_far " << s.piece.rho_far
                   << " batch " << batch.emission[i] << " scalar " << o.emission << " ref "
                   << ref.emission.hi << " target " << exact_batch_target());
    REQUIRE(std::isfinite(intensity));
    CHECK(batch.branch[i] == o.branch);
    CHECK(batch.terms[i] == o.terms);
    CHECK(batch.converged[i] == (o.converged ? 1 : 0));
    CHECK(within(intensity, ref.intensity, Tolerances::exact_rel));
    CHECK(within(batch.emission[i], ref.emission, Tolerances::exact_rel));
    CHECK(within(batch.transmittance[i], ref.transmittance, Tolerances::exact_rel));
    worst = std::max(worst, relative_error(batch.emission[i], ref.emission));
    if (o.emission != 0.0)
      worst_vs_scalar = std::max(worst_vs_scalar, relative_error(batch.emission[i], o.emission));
    if (std::fabs(ref.emission.hi) > 1e-290) {
      ulps_batch.push_back(ulp_error(batch.emission[i], ref.emission));
      ulps_scalar.push_back(ulp_error(o.emission, ref.emission));
    }
  }
  for (const char* b : {"transparent", "thin_series", "q2_series", "erfcx", "dawson"}) {
    INFO("branch " << b);
    CHECK(branches[b] > 0);
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double med_batch = median(ulps_batch), med_scalar = median(ulps_scalar);
  WARN("exact_batch (" << exact_batch_target() << "): worst emission rel " << worst << ", vs scalar "
                       << worst_vs_scalar << ", median ulp " << med_batch << " (scalar " << med_scalar << ")");
  CHECK(worst <= Tolerances::exact_rel);
  CHECK(worst_vs_scalar <= SimdTolerances::batch_vs_scalar_rel);
  CHECK(med_batch <= Tolerances::exact_median_ulp);
  CHECK(med_batch <= med_scalar + 1.0);  // issue 17: median within 1 ulp of the scalar path
}

}  // namespace

TEST_CASE("exact_batch against the reference and exact_piece, all regimes in one batch",
          "[exact_batch]") {
  check_all_regimes_in_one_batch();
}

TEST_CASE("exact_batch on every SIMD target this CPU runs, all regimes in one batch", "[exact_batch][simd_targets]") {
  for_each_simd_target([] {
    INFO("dispatched target " << exact_batch_target());
    check_all_regimes_in_one_batch();
  });
}

TEST_CASE("exact_batch: sizes that leave vector tails, edge pieces, results in place",
          "[exact_batch]") {
  // Pieces on every branch edge: T = 0, T exactly kThinDepth, B == 0, |B| at kQ2Relative A^2,
  // huge T, tiny T, denormal density.
  std::vector<ChannelPiece> edge = {
      {1.0, 0.0, 0.0, 1.0, 2.0},                       // transparent
      {1.0, 1.0, 1.0, 0.5, 0.5},                       // T = 1: thin
      {2.0, 1.0, 1.0, 0.5, 1.5},                       // T = 2, B = 0: q2 series, m0 alone
      {1.0, 3.0 + 0x1p-20, 3.0, 1.0, 1.0},             // |B| tiny: q2 series
      {1.0, 40.0, 1.0, 1.0, 2.0},                      // erfcx
      {1.0, 1.0, 40.0, 1.0, 2.0},                      // dawson
      {1e10, 1e290, 1e280, 1.0, 3.0},                  // T ~ 5e299
      {1e-5, 1e-300, 2e-300, 1.0, 1.0},                // T ~ 1e-305
      {1.0, 5e-324, 0.0, 1.0, 1.0},                    // denormal
      {3.0, 1e6, 2e5, 0.25, 4.0},                      // thick, erfcx with huge arguments
      {3.0, 2e5, 1e6, 0.25, 4.0},                      // thick, dawson
  };
  std::vector<ReferencePiece> refs;
  for (const ChannelPiece& p : edge) refs.push_back(reference_piece(p, 0.5));
  for (std::size_t n : {0u, 1u, 3u, 7u, 8u, 9u, 17u, 33u, 100u}) {
    Batch batch;
    for (std::size_t i = 0; i < n; ++i) batch.add(edge[i % edge.size()]);
    batch.run();
    for (std::size_t i = 0; i < n; ++i) {
      const ChannelPiece& p = edge[i % edge.size()];
      const PieceOptics o = exact_piece(p);
      const ReferencePiece& ref = refs[i % edge.size()];
      INFO("n " << n << " i " << i << " branch " << branch_name(o.branch));
      CHECK(batch.branch[i] == o.branch);
      CHECK(within(batch.emission[i], ref.emission, Tolerances::exact_rel));
      CHECK(within(batch.transmittance[i], ref.transmittance, Tolerances::exact_rel));
      if (o.branch == ExactBranch::transparent) {
        CHECK(batch.transmittance[i] == 1.0);
        CHECK(batch.emission[i] == 0.0);
      }
    }
  }
}

TEST_CASE("ExactIntegrator: the batch path and path=scalar agree on rays", "[exact_batch]") {
  std::mt19937_64 rng(11);
  const auto batch_spec = parse_method_spec("exact");
  const auto scalar_spec = parse_method_spec("exact:path=scalar");
  for (const Regime regime : ray_regimes()) {
    for (int i = 0; i < 4; ++i) {
      const RaySample s = sample_ray(regime, rng);
      Diagnostics db, ds;
      const RayResult rb = make_integrator(batch_spec, s.transfer)->integrate(s.ray, &db);
      const RayResult rs = make_integrator(scalar_spec, s.transfer)->integrate(s.ray, &ds);
      const ReferenceRay ref = reference_ray(s.transfer, s.ray);
      CHECK(db.branches == ds.branches);
      CHECK(db.stats == ds.stats);
      for (int c = 0; c < kChannels; ++c) {
        INFO("regime " << regime_name(regime) << " sample " << i << " channel " << c);
        CHECK(within(rb.intensity[c], ref.intensity[c], Tolerances::exact_rel));
        CHECK(within(rb.transmittance[c], ref.transmittance[c], Tolerances::exact_rel));
        if (!underflowed(ref.intensity[c]))
          CHECK(relative_error(rb.intensity[c], rs.intensity[c]) <= SimdTolerances::batch_vs_scalar_rel);
      }
    }
  }
}

namespace {

// A grey batch (one density per piece, three kappa columns) against the channel batch with the
// density repeated in every channel: the same transmittances and emissions, bit for bit. Sizes
// leave vector tails and cross the 4,096-entry chunks of both layouts.
void check_grey_matches_channels() {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(0.0, 4.0);
  const std::vector<Regime> regimes = all_regimes();
  const auto bits_equal = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  for (const std::size_t n : {0u, 1u, 5u, 8u, 9u, 17u, 150u, 4096u * 3u + 7u}) {
    GreyPieceColumns grey;
    Batch channels;
    for (std::size_t i = 0; i < n; ++i) {
      const ChannelPiece p = sample_piece(regimes[i % regimes.size()], rng).piece;
      const double far[2 * kChannels] = {p.rho_far, p.rho_far, p.rho_far, p.kappa_far, u(rng), u(rng)};
      const double exit[2 * kChannels] = {p.rho_exit, p.rho_exit, p.rho_exit, p.kappa_exit, u(rng), u(rng)};
      grey.push(p.length, far, exit);
      for (int c = 0; c < kChannels; ++c)
        channels.add(ChannelPiece{p.length, p.rho_far, p.rho_exit, far[kChannels + c], exit[kChannels + c]});
    }
    channels.run();
    std::vector<double> tr(n, -1.0);
    std::array<std::vector<double>, kChannels> em;
    GreyPieceView in{grey.length.data(), grey.rho_far.data(), grey.rho_exit.data(), {}, {}, n};
    GreyOpticsColumns out{tr.data(), {}};
    for (std::size_t c = 0; c < kChannels; ++c) {
      em[c].assign(n, -1.0);
      in.kappa_far[c] = grey.kappa_far[c].data();
      in.kappa_exit[c] = grey.kappa_exit[c].data();
      out.emission[c] = em[c].data();
    }
    exact_batch(in, out);
    long mismatches = 0, transparent = 0;
    for (std::size_t k = 0; k < n; ++k) {
      transparent += channels.branch[kChannels * k] == ExactBranch::transparent;
      for (std::size_t c = 0; c < kChannels; ++c) {
        mismatches += !bits_equal(tr[k], channels.transmittance[kChannels * k + c]);
        mismatches += !bits_equal(em[c][k], channels.emission[kChannels * k + c]);
      }
    }
    INFO("n " << n);
    CHECK(mismatches == 0);
    if (n > 1000) CHECK(transparent < static_cast<long>(n));  // the kernels ran, not only the transparent lanes
  }
}

}  // namespace

TEST_CASE("exact_batch: grey columns give the channel columns' results bit for bit", "[exact_batch]") {
  check_grey_matches_channels();
}

TEST_CASE("exact_batch: grey columns on every SIMD target this CPU runs", "[exact_batch][simd_targets]") {
  for_each_simd_target([] {
    INFO("dispatched target " << exact_batch_target());
    check_grey_matches_channels();
  });
}

TEST_CASE("ExactIntegrator: a grey medium's batch path gives the channel path's rays bit for bit", "[exact_batch]") {
  // Without diagnostics a grey transfer function takes the grey batch; with them, the channel
  // batch (which reports a branch per piece-channel). Both must give the same bits, and the
  // reference's accuracy.
  std::mt19937_64 rng(23);
  const auto spec = parse_method_spec("exact");
  long rays = 0;
  for (const Regime regime : ray_regimes()) {
    for (int i = 0; i < 4; ++i) {
      RaySample s = sample_ray(regime, rng);
      s.transfer.density[1] = s.transfer.density[2] = s.transfer.density[0];
      REQUIRE(s.transfer.grey());
      const auto integrator = make_integrator(spec, s.transfer);
      Diagnostics diag;
      const RayResult grey = integrator->integrate(s.ray, nullptr);
      const RayResult channels = integrator->integrate(s.ray, &diag);
      const ReferenceRay ref = reference_ray(s.transfer, s.ray);
      for (int c = 0; c < kChannels; ++c) {
        INFO("regime " << regime_name(regime) << " sample " << i << " channel " << c);
        CHECK(std::memcmp(&grey.intensity[c], &channels.intensity[c], sizeof(double)) == 0);
        CHECK(std::memcmp(&grey.transmittance[c], &channels.transmittance[c], sizeof(double)) == 0);
        CHECK(within(grey.intensity[c], ref.intensity[c], Tolerances::exact_rel));
        CHECK(within(grey.transmittance[c], ref.transmittance[c], Tolerances::exact_rel));
      }
      ++rays;
    }
  }
  CHECK(rays > 10);
}

TEST_CASE("ExactIntegrator: integrate_many gives each ray's integrate results bit for bit", "[exact_batch]") {
  // The render integrates a tile's rays in one call (the grey path: one kernel batch over all
  // their pieces). Rays of every regime, an empty ray among them, under one grey and one
  // coloured transfer function.
  std::mt19937_64 rng(29);
  const auto spec = parse_method_spec("exact");
  std::vector<Ray> rays;
  for (const Regime regime : ray_regimes())
    for (int i = 0; i < 3; ++i) rays.push_back(sample_ray(regime, rng).ray);
  rays.insert(rays.begin() + 3, Ray{});
  for (const bool grey : {true, false}) {
    RaySample s = sample_ray(ray_regimes().front(), rng);
    if (grey) s.transfer.density[1] = s.transfer.density[2] = s.transfer.density[0];
    REQUIRE(s.transfer.grey() == grey);
    const auto integrator = make_integrator(spec, s.transfer);
    std::vector<RayResult> together(rays.size());
    integrator->integrate_many(rays.data(), rays.size(), together.data());
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const RayResult one = integrator->integrate(rays[i], nullptr);
      for (int c = 0; c < kChannels; ++c) {
        INFO("grey " << grey << " ray " << i << " channel " << c);
        CHECK(std::memcmp(&together[i].intensity[c], &one.intensity[c], sizeof(double)) == 0);
        CHECK(std::memcmp(&together[i].transmittance[c], &one.transmittance[c], sizeof(double)) == 0);
      }
    }
  }
}

namespace {

// Runs of thin pieces (0 < T <= 1, the render's common regime) take exact_batch's in-order
// thin pass when no introspection column is asked for; with one asked for, the grouped path
// (classification, branch groups, expansion back). Both must give the same bits, for the
// channel and the grey columns, with a piece of another branch (or none) at the start, in the
// middle or in the last partial pair, at sizes that leave tails and cross the 4,096-entry chunks.
void check_thin_in_order_matches_groups() {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto bits_equal = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  const auto thin_piece = [&]() {
    // T = L (rho_exit + rho_far)/2 from 1e-6 to 1, a quarter with rho_far == rho_exit (B = 0)
    const double T = std::pow(10.0, -6.0 * u(rng));
    const double share = u(rng) < 0.25 ? 0.5 : u(rng);
    const double length = 0.01 + u(rng);
    return ChannelPiece{length, 2.0 * T * share / length, 2.0 * T * (1.0 - share) / length, u(rng), 4.0 * u(rng)};
  };
  const std::vector<ChannelPiece> others = {
      {1.0, 1.5, 1.5, 0.5, 0.5},                                         // T = 1.5: q2 series
      {1.0, 0.0, 0.0, 1.0, 2.0},                                         // transparent
      {1.0, 40.0, 1.0, 1.0, 2.0},                                        // erfcx
      {1.0, std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0, 1.0},   // NaN density
  };
  long in_order_pieces = 0;
  for (const std::size_t n : {1u, 15u, 16u, 17u, 33u, 100u, 4096u + 40u}) {
    for (const long at : {-1L, 0L, static_cast<long>(n / 2), static_cast<long>(n) - 1}) {
      if (at >= static_cast<long>(n)) continue;
      Batch with_groups;  // introspection asked for: the grouped path
      std::vector<double> kappa_far_g[kChannels], kappa_exit_g[kChannels];
      for (std::size_t i = 0; i < n; ++i) {
        const ChannelPiece p =
            static_cast<long>(i) == at ? others[static_cast<std::size_t>(i + n) % others.size()] : thin_piece();
        with_groups.add(p);
        kappa_far_g[0].push_back(p.kappa_far);
        kappa_exit_g[0].push_back(p.kappa_exit);
        for (int c = 1; c < kChannels; ++c) {
          kappa_far_g[c].push_back(u(rng));
          kappa_exit_g[c].push_back(u(rng));
        }
      }
      with_groups.run();
      // the channel columns without introspection
      std::vector<double> tr(n, -1.0), em(n, -1.0);
      exact_batch({with_groups.length.data(), with_groups.rho_far.data(), with_groups.rho_exit.data(),
                   with_groups.kappa_far.data(), with_groups.kappa_exit.data(), n},
                  {tr.data(), em.data()});
      // the grey columns (density once, three kappas), against the grouped channel path channel by channel
      std::vector<double> grey_tr(n, -1.0);
      std::array<std::vector<double>, kChannels> grey_em;
      GreyPieceView in{with_groups.length.data(), with_groups.rho_far.data(), with_groups.rho_exit.data(), {}, {}, n};
      GreyOpticsColumns out{grey_tr.data(), {}};
      Batch channel_groups[kChannels];
      for (std::size_t c = 0; c < kChannels; ++c) {
        grey_em[c].assign(n, -1.0);
        in.kappa_far[c] = kappa_far_g[c].data();
        in.kappa_exit[c] = kappa_exit_g[c].data();
        out.emission[c] = grey_em[c].data();
        for (std::size_t i = 0; i < n; ++i)
          channel_groups[c].add(ChannelPiece{with_groups.length[i], with_groups.rho_far[i], with_groups.rho_exit[i],
                                             kappa_far_g[c][i], kappa_exit_g[c][i]});
        channel_groups[c].run();
      }
      exact_batch(in, out);
      long mismatches = 0, thin = 0;
      for (std::size_t i = 0; i < n; ++i) {
        thin += with_groups.branch[i] == ExactBranch::thin_series;
        mismatches += !bits_equal(tr[i], with_groups.transmittance[i]);
        mismatches += !bits_equal(em[i], with_groups.emission[i]);
        for (std::size_t c = 0; c < kChannels; ++c) {
          mismatches += !bits_equal(grey_tr[i], channel_groups[c].transmittance[i]);
          mismatches += !bits_equal(grey_em[c][i], channel_groups[c].emission[i]);
        }
      }
      INFO("n " << n << " other piece at " << at << " target " << exact_batch_target());
      CHECK(mismatches == 0);
      CHECK(thin == static_cast<long>(n) - (at >= 0 ? 1 : 0));  // the generator's pieces are all thin
      in_order_pieces += thin;
    }
  }
  CHECK(in_order_pieces > 4096);
}

}  // namespace

TEST_CASE("exact_batch: runs of thin pieces in order give the grouped path's results bit for bit",
          "[exact_batch]") {
  check_thin_in_order_matches_groups();
}

TEST_CASE("exact_batch: runs of thin pieces on every SIMD target this CPU runs", "[exact_batch][simd_targets]") {
  for_each_simd_target([] {
    INFO("dispatched target " << exact_batch_target());
    check_thin_in_order_matches_groups();
  });
}
