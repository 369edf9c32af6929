#pragma once
// The library's one thread pool. parallel_for(count, threads, fn) runs fn for every item of
// [0, count) on worker threads that take the next item from an atomic counter (a dynamic
// schedule, so rows of unequal cost balance). threads = 0: all hardware threads; the pool never
// has more workers than items. The first exception a body throws stops the handing out of items
// and is rethrown to the caller once every worker has stopped.
//
// Results are independent of the thread count when each item writes only its own outputs and
// draws its random numbers from a seed of its own (index-seeded), and per-worker partial results
// are merged in an order that does not depend on which worker ran what (tests/test_parallel.cpp).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace rayint {

// std::thread::hardware_concurrency(): 0 when unknown.
inline unsigned hardware_threads() { return std::thread::hardware_concurrency(); }

// The thread count `threads` asks for: itself, or (0) all hardware threads, at least 1.
inline unsigned resolve_threads(unsigned threads) {
  return threads != 0 ? threads : std::max(1u, hardware_threads());
}

// How many workers parallel_for(count, threads, ...) runs: worker indices are below this.
inline unsigned parallel_workers(long long count, unsigned threads) {
  const long long items = std::max(1LL, count);
  return static_cast<unsigned>(std::min<long long>(resolve_threads(threads), items));
}

namespace detail {

// fn(item, worker) when fn takes both, else fn(item).
template <class Fn>
void call_item(Fn& fn, long long item, unsigned worker) {
  if constexpr (std::is_invocable_v<Fn&, long long, unsigned>)
    fn(item, worker);
  else
    fn(item);
}

// Runs the items on `workers` threads of their own. When `tick` is given, the calling thread
// calls it every `tick_seconds` until the workers are done; otherwise it only waits.
template <class Fn, class Tick>
void run_pool(long long count, unsigned workers, Fn& fn, double tick_seconds, Tick* tick) {
  std::atomic<long long> next{0};
  std::mutex mutex;
  std::condition_variable finished;
  std::exception_ptr error;
  unsigned running = workers;  // guarded by mutex
  const auto fail = [&](std::exception_ptr e) {
    std::lock_guard<std::mutex> lock(mutex);
    if (!error) error = e;
    next = count;  // hand out no more items
  };
  const auto work = [&](unsigned w) {
    try {
      for (long long i = next++; i < count; i = next++) call_item(fn, i, w);
    } catch (...) {
      fail(std::current_exception());
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (--running == 0) finished.notify_all();
  };
  std::vector<std::thread> pool;
  pool.reserve(workers);
  try {
    for (unsigned w = 0; w < workers; ++w) pool.emplace_back(work, w);
  } catch (...) {  // a thread could not be started: stop the others, then report it
    fail(std::current_exception());
    std::lock_guard<std::mutex> lock(mutex);
    running -= workers - static_cast<unsigned>(pool.size());
  }
  if (tick) {
    const auto interval = std::chrono::duration<double>(tick_seconds);
    bool ticking = true;  // until tick() throws
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished.wait_for(lock, interval, [&] { return running == 0; })) {
      if (!ticking) continue;
      lock.unlock();
      try {
        (*tick)();
      } catch (...) {
        ticking = false;
        fail(std::current_exception());
      }
      lock.lock();
    }
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace detail

// fn(item, worker) -- or fn(item) -- for every item in [0, count); worker is in
// [0, parallel_workers(count, threads)), for per-worker scratch and partial sums. With one
// worker the items run on the calling thread, in order.
template <class Fn>
void parallel_for(long long count, unsigned threads, Fn&& fn) {
  if (count <= 0) return;
  const unsigned workers = parallel_workers(count, threads);
  if (workers == 1) {
    for (long long i = 0; i < count; ++i) detail::call_item(fn, i, 0);
    return;
  }
  detail::run_pool<Fn, void()>(count, workers, fn, 0.0, nullptr);
}

// Like parallel_for, but item i always goes to worker i % parallel_workers(count, threads): what
// a worker adds up then depends on the thread count alone, not on which rows it happened to take,
// so sums of per-worker parts are the same bit for bit from run to run (the loss gradients,
// render/mesh_gradient.cpp and scene/grid_loss_gradient.cpp). Rows of an image interleave, so
// the workers' shares stay balanced.
template <class Fn>
void parallel_for_striped(long long count, unsigned threads, Fn&& fn) {
  if (count <= 0) return;
  const unsigned workers = parallel_workers(count, threads);
  parallel_for(workers, workers, [&](long long stripe, unsigned) {
    for (long long i = stripe; i < count; i += workers) detail::call_item(fn, i, static_cast<unsigned>(stripe));
  });
}

// The same as parallel_for, with a monitor: the calling thread runs no items but calls tick() every
// `tick_seconds` while the workers run (not after they are done), so a progress callback runs
// on the caller's thread only and needs no locking. An exception from tick() is carried like
// one from an item.
template <class Fn, class Tick>
void parallel_for(long long count, unsigned threads, Fn&& fn, double tick_seconds, Tick&& tick) {
  if (count <= 0) return;
  detail::run_pool(count, parallel_workers(count, threads), fn, tick_seconds, &tick);
}

}  // namespace rayint
