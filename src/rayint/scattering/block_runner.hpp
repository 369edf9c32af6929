#pragma once
// Runs independent Monte Carlo sample blocks on a pool of std::threads and merges their sums in
// block order. Block b always draws from block_rng(seed, b) and always holds the same samples,
// so the merged result is bit-for-bit the same for any thread count (tested in
// tests/test_scatter_slab.cpp).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "rayint/scattering/estimate.hpp"

namespace rayint {

// threads <= 0: std::thread::hardware_concurrency(). `run_block(b)` must be thread-safe and
// depend only on b. Rethrows the first exception a block threw.
inline ScoreSums run_blocks(std::size_t blocks, int threads,
                            const std::function<ScoreSums(std::size_t)>& run_block) {
  std::vector<ScoreSums> results(blocks);
  std::size_t n_threads = threads > 0 ? static_cast<std::size_t>(threads)
                                      : std::max(1u, std::thread::hardware_concurrency());
  n_threads = std::max<std::size_t>(1, std::min(n_threads, blocks));
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    for (;;) {
      const std::size_t b = next.fetch_add(1);
      if (b >= blocks) return;
      try {
        results[b] = run_block(b);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = blocks;
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < n_threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  ScoreSums total = results.empty() ? ScoreSums() : ScoreSums(results.front().size());
  for (const auto& r : results) total.merge(r);
  return total;
}

}  // namespace rayint

namespace rayint {

// Runs body(b) for b in [0, blocks) on a pool of threads (threads <= 0: all cores); each b
// must write only its own outputs. Rethrows the first exception.
inline void parallel_for_blocks(std::size_t blocks, int threads,
                                const std::function<void(std::size_t)>& body) {
  std::size_t n_threads = threads > 0 ? static_cast<std::size_t>(threads)
                                      : std::max(1u, std::thread::hardware_concurrency());
  n_threads = std::max<std::size_t>(1, std::min(n_threads, blocks));
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    for (;;) {
      const std::size_t b = next.fetch_add(1);
      if (b >= blocks) return;
      try {
        body(b);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = blocks;
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < n_threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace rayint
