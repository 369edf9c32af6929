#pragma once
// An allocator for large arrays written once in full (issue 33): a block of at least 4 MiB is
// mapped 2 MiB-aligned and offered to the kernel's transparent huge pages (madvise), so writing it
// takes one page fault per 2 MiB instead of one per 4 KiB. Smaller blocks: std::allocator.
#include <cstddef>
#include <memory>
#include <new>

#include <sys/mman.h>

namespace rayint {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHuge = std::size_t{2} << 20;
  static constexpr std::size_t kMin = std::size_t{4} << 20;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  static std::size_t mapped_bytes(std::size_t n) { return (n * sizeof(T) + kHuge - 1) / kHuge * kHuge; }
  T* allocate(std::size_t n) {
    if (n * sizeof(T) < kMin) return std::allocator<T>().allocate(n);
    const std::size_t bytes = mapped_bytes(n);
    void* raw = mmap(nullptr, bytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    auto* base = static_cast<char*>(raw);
    const std::size_t lead = (kHuge - reinterpret_cast<std::uintptr_t>(base) % kHuge) % kHuge;
    if (lead > 0) munmap(base, lead);
    if (kHuge - lead > 0) munmap(base + lead + bytes, kHuge - lead);
    madvise(base + lead, bytes, MADV_HUGEPAGE);
    return reinterpret_cast<T*>(base + lead);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kMin) return std::allocator<T>().deallocate(p, n);
    munmap(p, mapped_bytes(n));
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

}  // namespace rayint
