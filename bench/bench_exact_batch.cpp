// Throughput of the batched exact path (integrators/exact_batch.*) in piece-channels per second,
// one and two threads, against the scalar exact_piece on the same pieces; and the vector
// erfcx/Dawson against libcerf per call.
// Run: build/bench/rayint_bench --benchmark_filter='batch|simd|cerf' --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median; items_per_second is
//      piece-channels per second, summed over threads)
#include <benchmark/benchmark.h>

#include <hwy/targets.h>

#include <algorithm>
#include <random>
#include <vector>

#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/special/erfcx_simd.hpp"
#include "rayint/special/special_functions.hpp"

namespace {

// 512 pieces of every regime, shuffled (the mix of BM_exact_piece_mixed in bench_exact.cpp),
// or 4096 of one regime.
struct Columns {
  std::vector<double> length, rho_far, rho_exit, kappa_far, kappa_exit;
  std::size_t size() const { return length.size(); }
};

Columns columns(int regime_index) {
  std::vector<rayint::ChannelPiece> pieces;
  for (std::size_t r = 0; r < rayint::all_regimes().size(); ++r) {
    if (regime_index >= 0 && static_cast<std::size_t>(regime_index) != r) continue;
    std::mt19937_64 rng(12345);
    const int count = regime_index >= 0 ? 4096 : 512;
    for (int i = 0; i < count; ++i) pieces.push_back(rayint::sample_piece(rayint::all_regimes()[r], rng).piece);
  }
  if (regime_index < 0) std::shuffle(pieces.begin(), pieces.end(), std::mt19937_64(99));
  Columns c;
  for (const auto& p : pieces) {
    c.length.push_back(p.length);
    c.rho_far.push_back(p.rho_far);
    c.rho_exit.push_back(p.rho_exit);
    c.kappa_far.push_back(p.kappa_far);
    c.kappa_exit.push_back(p.kappa_exit);
  }
  return c;
}

void run_batch(benchmark::State& state, const Columns& c) {
  std::vector<double> tr(c.size()), em(c.size());
  for (auto _ : state) {
    rayint::exact_batch({c.length.data(), c.rho_far.data(), c.rho_exit.data(), c.kappa_far.data(),
                         c.kappa_exit.data(), c.size()},
                        {tr.data(), em.data()});
    benchmark::DoNotOptimize(em.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(c.size()));
  state.SetLabel(rayint::exact_batch_target());
}

// The same pieces in calls of state.range(0) piece-channels (a ray's worth is ~150 in the
// 100k-tet ball render): what a small batch costs per piece-channel.
void BM_exact_batch_mixed_calls(benchmark::State& state) {
  static const Columns c = columns(-1);
  const auto call = static_cast<std::size_t>(state.range(0));
  std::vector<double> tr(c.size()), em(c.size());
  for (auto _ : state) {
    for (std::size_t i = 0; i < c.size(); i += call) {
      const std::size_t n = std::min(call, c.size() - i);
      rayint::exact_batch({c.length.data() + i, c.rho_far.data() + i, c.rho_exit.data() + i, c.kappa_far.data() + i,
                           c.kappa_exit.data() + i, n},
                          {tr.data() + i, em.data() + i});
    }
    benchmark::DoNotOptimize(em.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(c.size()));
}

void BM_exact_batch_mixed(benchmark::State& state) {
  static const Columns c = columns(-1);
  run_batch(state, c);
}

// The same mixed pieces as a grey medium (GreyPieceView): each piece's density once, three
// channels' kappas (the mixed kappa and two more). items_per_second counts piece-channels (3 per
// piece), as the channel benchmarks do, so the two are comparable per channel of output.
void BM_exact_batch_grey_mixed(benchmark::State& state) {
  static const Columns c = columns(-1);
  static const std::vector<double> kappa_g = [] {
    std::vector<double> k(c.size());
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = 0.5 * c.kappa_far[(i + 1) % k.size()];
    return k;
  }();
  std::vector<double> tr(c.size()), em_r(c.size()), em_g(c.size()), em_b(c.size());
  const rayint::GreyPieceView in{c.length.data(),
                                 c.rho_far.data(),
                                 c.rho_exit.data(),
                                 {c.kappa_far.data(), kappa_g.data(), c.kappa_exit.data()},
                                 {c.kappa_exit.data(), c.kappa_far.data(), kappa_g.data()},
                                 c.size()};
  const rayint::GreyOpticsColumns out{tr.data(), {em_r.data(), em_g.data(), em_b.data()}};
  for (auto _ : state) {
    rayint::exact_batch(in, out);
    benchmark::DoNotOptimize(em_b.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 3 * static_cast<long>(c.size()));
  state.SetLabel(rayint::exact_batch_target());
}

// The mixed batch on the AVX2 target, as on a CPU without AVX-512 (most desktops): one thread;
// the dispatch is restored afterwards.
void BM_exact_batch_mixed_avx2(benchmark::State& state) {
  static const Columns c = columns(-1);
  if ((hwy::SupportedTargets() & HWY_AVX2) == 0) {
    state.SkipWithError("the CPU has no AVX2");
    return;
  }
  hwy::SetSupportedTargetsForTest(HWY_AVX2);
  run_batch(state, c);
  hwy::SetSupportedTargetsForTest(0);
}

void BM_exact_batch_regime(benchmark::State& state) {
  const Columns c = columns(static_cast<int>(state.range(0)));
  run_batch(state, c);
  state.SetLabel(rayint::regime_name(rayint::all_regimes()[static_cast<std::size_t>(state.range(0))]) +
                 " " + rayint::exact_batch_target());
}

// The scalar reference on the same mixed columns, same threads: the ratio within one run.
void BM_exact_scalar_loop_mixed(benchmark::State& state) {
  static const Columns c = columns(-1);
  std::vector<double> tr(c.size()), em(c.size());
  for (auto _ : state) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      const rayint::PieceOptics o = rayint::exact_piece(
          {c.length[i], c.rho_far[i], c.rho_exit[i], c.kappa_far[i], c.kappa_exit[i]});
      tr[i] = o.transmittance;
      em[i] = o.emission;
    }
    benchmark::DoNotOptimize(em.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(c.size()));
}

std::vector<double> special_args() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x(4096);
  for (auto& v : x) v = std::exp(u(rng) * 9.0 - 4.0);  // 0.018 .. 148: both regions
  return x;
}

// One vector function of special/erfcx_simd.hpp over the arguments (negated for Exp and Expm1,
// whose arguments in the batch are -T and -tau).
void run_array(benchmark::State& state, void (*f)(const double*, double*, std::size_t), bool negate) {
  std::vector<double> x = special_args();
  if (negate)
    for (auto& v : x) v = -v;
  std::vector<double> y(x.size());
  for (auto _ : state) {
    f(x.data(), y.data(), x.size());
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(x.size()));
  state.SetLabel(rayint::special::simd_target_name());
}

void BM_erfcx_simd(benchmark::State& state) { run_array(state, rayint::special::erfcx_array, false); }
void BM_dawson_simd(benchmark::State& state) { run_array(state, rayint::special::dawson_array, false); }
// Highway's Exp and Expm1 (contrib/math): every batch piece takes one Exp (its transmittance)
// and one or two Expm1.
void BM_exp_simd(benchmark::State& state) { run_array(state, rayint::special::exp_array, true); }
void BM_expm1_simd(benchmark::State& state) { run_array(state, rayint::special::expm1_array, true); }

// The same arguments through a scalar function (libcerf's), one direct call per argument (a
// template argument, so no call through a pointer is timed).
template <double (*f)(double)>
void run_scalar(benchmark::State& state) {
  const std::vector<double> x = special_args();
  std::vector<double> y(x.size());
  for (auto _ : state) {
    for (std::size_t i = 0; i < x.size(); ++i) y[i] = f(x[i]);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(x.size()));
}

void BM_erfcx_cerf(benchmark::State& state) { run_scalar<rayint::special::erfcx>(state); }
void BM_dawson_cerf(benchmark::State& state) { run_scalar<rayint::special::dawson>(state); }

}  // namespace

BENCHMARK(BM_exact_batch_mixed)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK(BM_exact_batch_mixed_avx2)->UseRealTime();
BENCHMARK(BM_exact_batch_grey_mixed)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK(BM_exact_batch_mixed_calls)->Arg(48)->Arg(150)->Arg(600)->Arg(4096);
BENCHMARK(BM_exact_scalar_loop_mixed)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK(BM_exact_batch_regime)->DenseRange(0, static_cast<int>(rayint::all_regimes().size()) - 1);
BENCHMARK(BM_erfcx_simd);
BENCHMARK(BM_dawson_simd);
BENCHMARK(BM_exp_simd);
BENCHMARK(BM_expm1_simd);
BENCHMARK(BM_erfcx_cerf);
BENCHMARK(BM_dawson_cerf);
