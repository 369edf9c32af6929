#pragma once
// An allocator for large arrays that are written in full right after they are allocated (issue
// 33: the mesh load's cell records and face records). A block of at least 1 MiB is mapped with
// MAP_POPULATE, so the kernel provides all its pages in the mmap call instead of one page fault
// per 4 KiB page at the first write (each fault cost ~1.5-2.5 us on the measurement VM;
// reports/scaling/NOTES.md round 10). Smaller blocks come from std::allocator. Only for arrays
// whose every page is written anyway: populating pages never touched would only cost.
//
// Measured and not taken: the same blocks in transparent huge pages (2 MiB-aligned,
// madvise(MADV_HUGEPAGE)): 4-7 ms less at 105k tets but 10-25% more at 1.05M and bimodal (the
// huge pages' clearing), NOTES.md round 10.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

#include <sys/mman.h>

namespace rayint {

template <class T>
struct PrefaultedAllocator {
  using value_type = T;
  static constexpr std::size_t kMinBytes = std::size_t{1} << 20;
  PrefaultedAllocator() = default;
  template <class U>
  PrefaultedAllocator(const PrefaultedAllocator<U>&) {}
  T* allocate(std::size_t n) {
    if (n * sizeof(T) < kMinBytes) return std::allocator<T>().allocate(n);
    void* p = mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kMinBytes) return std::allocator<T>().deallocate(p, n);
    munmap(p, n * sizeof(T));
  }
  template <class U>
  bool operator==(const PrefaultedAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const PrefaultedAllocator<U>&) const { return false; }
};

// The same for a std::vector that has its own allocator (TetMesh::tets, the adjacency, ...): after
// `reserve`, the pages of its whole capacity are prefaulted writable with one
// madvise(MADV_POPULATE_WRITE) call (Linux 5.14+; elsewhere the call fails and the pages fault in
// as before). Only for a capacity of at least 256 KiB that is then written in full (issue 33:
// each 4 KiB page faulted in one by one costs ~1-10 us on the Zen 5 VM, populated in one call a
// fraction of that; NOTES.md round 15). Values are not touched.
template <class Vector>
void prefault_capacity(Vector& v) {
  constexpr std::size_t kMinBytes = std::size_t{1} << 18;
  const std::size_t bytes = v.capacity() * sizeof(typename Vector::value_type);
  if (bytes < kMinBytes) return;
  const auto page = static_cast<std::uintptr_t>(4096);
  const auto begin = (reinterpret_cast<std::uintptr_t>(v.data()) + page - 1) & ~(page - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(v.data()) + bytes) & ~(page - 1);
#ifdef MADV_POPULATE_WRITE
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)begin;
  (void)end;
#endif
}

}  // namespace rayint
