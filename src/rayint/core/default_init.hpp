#pragma once
// An allocator whose `resize` leaves new elements of a trivial type uninitialised (default-
// initialised) instead of zero-filling them, for scratch buffers that are always written before
// they are read. Zero-filling touches every page at once: the batched exact kernel's per-thread
// scratch (~1.7 MB, integrators/exact_batch.cpp) cost ~850 page faults and a memset per thread in
// every process, of which a short render touches a few pages (reports/scaling/NOTES.md, round 11).
#include <memory>
#include <new>
#include <utility>

namespace rayint {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) {}
  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;  // default-initialised: no value written
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace rayint
