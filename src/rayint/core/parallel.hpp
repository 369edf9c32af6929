#pragma once
// Work over [0, count) shared by `threads` workers through an atomic counter (dynamic schedule,
// so rows of unequal cost balance). threads = 0: all hardware threads. The first exception
// thrown by a worker is rethrown after all have stopped.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rayint {

inline unsigned resolve_threads(unsigned threads) {
  return threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
}

// fn(item, worker) for every item; worker in [0, resolve_threads(threads)).
template <class Fn>
void parallel_for(long long count, unsigned threads, Fn&& fn) {
  const unsigned n = std::max(1u, std::min<unsigned>(resolve_threads(threads),
                                                     static_cast<unsigned>(std::max(1LL, count))));
  std::atomic<long long> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](unsigned w) {
    try {
      for (long long i = next++; i < count; i = next++) fn(i, w);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = count;
    }
  };
  if (n == 1) {
    worker(0);
  } else {
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < n; ++w) pool.emplace_back(worker, w);
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace rayint
