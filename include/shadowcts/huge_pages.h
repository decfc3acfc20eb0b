#pragma once
// Memory for a run's large arrays (a shadow volume per triangle, a TOP tree's nodes), backed by
// transparent huge pages where the kernel grants them on request (THP in "madvise" mode, the
// Debian default): a fresh array then costs one page fault per 2 MiB instead of one per 4 KiB.
// On the 2-core VMs this project runs on, the 4 KiB faults of ptsv's 230 MB of volumes at 1M
// triangles took about 300 ms of a 840 ms frame (simd/README.md). Embree asks for huge pages for
// its own large blocks in the same way.
#include <cstddef>
#include <new>
#include <vector>

namespace shadowcts {

// Arrays of at least this size go to huge pages (and are rounded up to a multiple of it).
inline constexpr std::size_t huge_page_bytes = std::size_t(2) << 20;

// Freed arrays of at least huge_page_bytes stay with the process, up to this many bytes in all,
// and serve the next request that fits (at most twice its size): a repeated run of a case then
// reuses its pages instead of having the kernel zero fresh ones. Not under ASan/MSan, which must
// see every free.
inline constexpr std::size_t max_idle_large_bytes = std::size_t(1) << 30;
bool large_blocks_are_reused();

// `bytes` aligned to `alignment` (a power of two up to huge_page_bytes), not initialized (a reused
// block holds what its last user left); freed by free_large. Throws std::bad_alloc.
void* allocate_large(std::size_t bytes, std::size_t alignment);
void free_large(void* p) noexcept;

// A std allocator over allocate_large.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_large(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t) noexcept { free_large(p); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace shadowcts
