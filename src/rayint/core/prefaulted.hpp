#pragma once
// An allocator for large arrays that are written in full right after they are allocated (issue
// 33: the mesh load's cell records and face records). A block of at least 1 MiB is mapped with
// MAP_POPULATE, so the kernel provides all its pages in the mmap call instead of one page fault
// per 4 KiB page at the first write (each fault cost ~1.5-2.5 us on the measurement VM;
// reports/scaling/NOTES.md round 10). Smaller blocks come from std::allocator. Only for arrays
// whose every page is written anyway: populating pages never touched would only cost.
//
// A block of at least 2 MiB is mapped in transparent huge pages (map_huge below): measured slower
// at 1.05M on the Intel VM (round 10), faster on the Zen 5 VM (round 15: the walk's records;
// round 16: every such block, the 1.05M load 1.1-1.4 -> 0.8 us/tet).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

#include <sys/mman.h>

namespace rayint {

// The pages of an already allocated block [p, p + bytes) that is about to be written in full (a
// malloc'd image, say), provided in one call (MADV_POPULATE_WRITE, Linux 5.14) instead of one page
// fault per 4 KiB at the first writes: only the whole pages inside the block, nothing written, and
// nothing done below 64 KiB or where the kernel refuses it (the writes then fault as before).
// Issue 33, round 15: a 512 x 512 image (6.3 MB of doubles) was ~1,500 faults at ~6-10 us each on
// the Zen 5 VM (reports/scaling/NOTES.md).
inline void populate_pages(void* p, std::size_t bytes) {
#ifdef MADV_POPULATE_WRITE
  constexpr std::uintptr_t kPage = 4096;
  if (bytes < (std::size_t{64} << 10)) return;
  const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) / kPage * kPage;
  const auto end = (reinterpret_cast<std::uintptr_t>(p) + bytes) / kPage * kPage;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)p;
  (void)bytes;
#endif
}

// A block of `bytes` (rounded up to 4 KiB) mapped 2 MiB-aligned, its whole 2 MiB pages advised
// MADV_HUGEPAGE (the partial last one stays in 4 KiB pages), then populated (MADV_POPULATE_WRITE).
// Issue 33, round 16 (reports/scaling/NOTES.md): on the Zen 5 VM the first write to a populated
// 4 KiB page still costs ~8 us (a 64 MiB memset after MAP_POPULATE: 124-159 ms, a second one 5 ms),
// to a populated 2 MiB page next to nothing (3 ms).
inline std::size_t huge_mapped_bytes(std::size_t bytes) {
  constexpr std::size_t kPage = std::size_t{4} << 10;
  return (bytes + kPage - 1) / kPage * kPage;
}
inline void* map_huge(std::size_t bytes) {
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  bytes = huge_mapped_bytes(bytes);
  // Map one huge page more than needed and cut the unaligned head and the tail away.
  void* raw = mmap(nullptr, bytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kHuge - 1) / kHuge * kHuge;
  if (aligned > start) munmap(raw, aligned - start);
  const std::size_t tail = start + kHuge - aligned;
  if (tail > 0) munmap(reinterpret_cast<void*>(aligned + bytes), tail);
  void* p = reinterpret_cast<void*>(aligned);
  madvise(p, bytes / kHuge * kHuge, MADV_HUGEPAGE);
#ifdef MADV_POPULATE_WRITE
  madvise(p, bytes, MADV_POPULATE_WRITE);
#endif
  return p;
}

template <class T>
struct PrefaultedAllocator {
  using value_type = T;
  static constexpr std::size_t kMinBytes = std::size_t{1} << 20;
  PrefaultedAllocator() = default;
  template <class U>
  PrefaultedAllocator(const PrefaultedAllocator<U>&) {}
  static constexpr std::size_t kHugeBytes = std::size_t{2} << 20;
  T* allocate(std::size_t n) {
    if (n * sizeof(T) < kMinBytes) return std::allocator<T>().allocate(n);
    if (n * sizeof(T) >= kHugeBytes) return static_cast<T*>(map_huge(n * sizeof(T)));
    void* p = mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kMinBytes) return std::allocator<T>().deallocate(p, n);
    munmap(p, n * sizeof(T) >= kHugeBytes ? huge_mapped_bytes(n * sizeof(T)) : n * sizeof(T));
  }
  template <class U>
  bool operator==(const PrefaultedAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const PrefaultedAllocator<U>&) const { return false; }
};

// The same for a std::vector that has its own allocator (TetMesh::tets, the adjacency, ...): after
// `reserve`, the pages of its whole capacity are prefaulted writable with one
// madvise(MADV_POPULATE_WRITE) call (Linux 5.14+; elsewhere the call fails and the pages fault in
// as before), the whole 2 MiB pages inside it advised MADV_HUGEPAGE first (round 16). Only for a
// capacity of at least 256 KiB that is then written in full (issue 33:
// each 4 KiB page faulted in one by one costs ~1-10 us on the Zen 5 VM, populated in one call a
// fraction of that; NOTES.md round 15). Values are not touched.
template <class Vector>
void prefault_capacity(Vector& v) {
  const std::size_t bytes = v.capacity() * sizeof(typename Vector::value_type);
  if (bytes < (std::size_t{1} << 18)) return;
  // The whole 2 MiB pages inside the block in huge pages (see map_huge; round 16).
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<std::uintptr_t>(v.data()) + kHuge - 1) / kHuge * kHuge;
  const auto end = (reinterpret_cast<std::uintptr_t>(v.data()) + bytes) / kHuge * kHuge;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  populate_pages(v.data(), bytes);
}

}  // namespace rayint
