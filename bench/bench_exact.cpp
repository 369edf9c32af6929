// Cost of the exact closed form per piece (one channel), per regime.
// Run: build/bench/rayint_bench --benchmark_filter=exact --benchmark_repetitions=5
//      --benchmark_report_aggregates_only=true      (quote the median)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_batch.hpp"

namespace {

std::vector<rayint::ChannelPiece> pieces_for(rayint::Regime regime) {
  std::mt19937_64 rng(12345);
  std::vector<rayint::ChannelPiece> v;
  for (int i = 0; i < 4096; ++i) v.push_back(rayint::sample_piece(regime, rng).piece);
  return v;
}

void BM_exact_piece(benchmark::State& state) {
  const auto regime = rayint::all_regimes()[static_cast<std::size_t>(state.range(0))];
  const auto pieces = pieces_for(regime);
  std::size_t i = 0;
  for (auto _ : state) {
    const rayint::PieceOptics o = rayint::exact_piece(pieces[i]);
    benchmark::DoNotOptimize(o.emission);
    benchmark::DoNotOptimize(o.transmittance);
    i = (i + 1) & 4095;
  }
  state.SetLabel(rayint::regime_name(regime));
  state.SetItemsProcessed(state.iterations());
}

// All regimes mixed in equal shares: the single "ns per piece" figure.
void BM_exact_piece_mixed(benchmark::State& state) {
  std::vector<rayint::ChannelPiece> pieces;
  for (const auto regime : rayint::all_regimes()) {
    const auto v = pieces_for(regime);
    pieces.insert(pieces.end(), v.begin(), v.begin() + 512);
  }
  std::shuffle(pieces.begin(), pieces.end(), std::mt19937_64(99));
  std::size_t i = 0;
  for (auto _ : state) {
    const rayint::PieceOptics o = rayint::exact_piece(pieces[i]);
    benchmark::DoNotOptimize(o.emission);
    i = (i + 1) % pieces.size();
  }
  state.SetItemsProcessed(state.iterations());
}

// 1,000,000 pieces, every regime in turn (generators mixed_regime_pieces, seed 2026), through
// exact_batch (the batched `exact`) from arrays: the C++ figure for the Python module's rayint.exact_pieces on
// the same pieces (scripts/examples/bench_exact_pieces.py). ns per piece = 1e9 / items_per_second.
void BM_exact_pieces_batch(benchmark::State& state) {
  const std::vector<rayint::ChannelPiece> pieces = rayint::mixed_regime_pieces(1000000, 2026);
  const std::size_t n = pieces.size();
  rayint::PieceColumnStore columns;
  const rayint::PieceColumns in = columns.assign(pieces.data(), n);
  std::vector<double> emission(n), transmittance(n);
  rayint::OpticsColumns out;
  out.emission = emission.data();
  out.transmittance = transmittance.data();
  for (auto _ : state) {
    rayint::exact_batch(in, out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

}  // namespace

BENCHMARK(BM_exact_pieces_batch)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_exact_piece)->DenseRange(0, static_cast<int>(rayint::all_regimes().size()) - 1);
BENCHMARK(BM_exact_piece_mixed);
BENCHMARK_MAIN();
