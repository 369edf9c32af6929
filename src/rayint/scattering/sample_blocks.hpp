#pragma once
// Independent Monte Carlo sample blocks run in parallel (core/parallel.hpp) and their sums merged
// in block order. Block b always draws from block_rng(seed, b) and always holds the same
// samples, so the merged result is bit-for-bit the same for any thread count (tested in
// tests/test_scatter_slab.cpp).
#include <cstddef>
#include <functional>
#include <vector>

#include "rayint/core/parallel.hpp"
#include "rayint/scattering/estimate.hpp"

namespace rayint {

// threads = 0: all cores. `run_block(b)` must be thread-safe and depend only on b. Rethrows
// the first exception a block threw.
inline ScoreSums sum_sample_blocks(std::size_t blocks, unsigned threads,
                                   const std::function<ScoreSums(std::size_t)>& run_block) {
  std::vector<ScoreSums> results(blocks);
  parallel_for(static_cast<long long>(blocks), threads, [&](long long b) {
    results[static_cast<std::size_t>(b)] = run_block(static_cast<std::size_t>(b));
  });
  ScoreSums total = results.empty() ? ScoreSums() : ScoreSums(results.front().size());
  for (const auto& r : results) total.merge(r);
  return total;
}

}  // namespace rayint
