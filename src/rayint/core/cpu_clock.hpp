#pragma once
// CPU time of the calling thread and of the whole process (POSIX clock_gettime), so that costs
// measured on a shared, oversubscribed machine are not inflated by other jobs the way wall time
// is. Thread time costs one clock read (~0.1-0.3 us); callers time whole rays or shadow rays.
#include <ctime>

namespace rayint {

inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace rayint
