#include "shadowcts/huge_pages.h"

#include <algorithm>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadowcts {

void* allocate_large(std::size_t bytes, std::size_t alignment) {
  alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
  const bool huge = bytes >= huge_page_bytes;
  if (huge) alignment = huge_page_bytes;
  // aligned_alloc wants a multiple of the alignment.
  const std::size_t rounded =
      (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  if (rounded < bytes) throw std::bad_alloc();
  void* p = std::aligned_alloc(alignment, rounded);
  if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where THP is off, the pages stay 4 KiB and nothing else changes.
  if (huge) madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

void free_large(void* p) noexcept {
  std::free(p);
}

}  // namespace shadowcts
