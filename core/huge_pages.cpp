#include "shadowcts/huge_pages.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <mutex>
#include <unordered_map>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadowcts {
namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define SHADOWCTS_SANITIZED_MEMORY 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define SHADOWCTS_SANITIZED_MEMORY 1
#endif

// A sanitizer must see every block freed and every fresh block uninitialized: no reuse there.
#if defined(SHADOWCTS_SANITIZED_MEMORY)
constexpr bool reuse = false;
#else
constexpr bool reuse = true;
#endif

// Freed huge blocks kept for the next request they fit, as an engine keeps its per-frame buffers:
// the kernel zeroes every fresh page, and at 1M triangles that was about an eighth of simd ptsv's
// frame on the 2-core VMs (256 MB of volumes per call; simd/README.md).
struct IdleBlocks {
  std::mutex mutex;
  std::unordered_map<void*, std::size_t> live;  // huge blocks handed out: their rounded size
  std::multimap<std::size_t, void*> idle;       // freed huge blocks by rounded size
  std::size_t idle_bytes = 0;
};

IdleBlocks& idle_blocks() {
  // Never destroyed: a static array's destructor may free into it during exit.
  static IdleBlocks* blocks = new IdleBlocks;
  return *blocks;
}

}  // namespace

bool large_blocks_are_reused() {
  return reuse;
}

void* allocate_large(std::size_t bytes, std::size_t alignment) {
  alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
  const bool huge = bytes >= huge_page_bytes;
  if (huge) alignment = huge_page_bytes;
  // aligned_alloc wants a multiple of the alignment.
  const std::size_t rounded =
      (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  if (rounded < bytes) throw std::bad_alloc();
  if (reuse && huge) {
    IdleBlocks& blocks = idle_blocks();
    const std::lock_guard lock(blocks.mutex);
    // The smallest idle block that fits, if it is at most twice the request.
    const auto fit = blocks.idle.lower_bound(rounded);
    if (fit != blocks.idle.end() && fit->first / 2 <= rounded) {
      void* p = fit->second;
      blocks.idle_bytes -= fit->first;
      blocks.live.emplace(p, fit->first);
      blocks.idle.erase(fit);
      return p;
    }
  }
  void* p = std::aligned_alloc(alignment, rounded);
  if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where THP is off, the pages stay 4 KiB and nothing else changes.
  if (huge) madvise(p, rounded, MADV_HUGEPAGE);
#endif
  if (reuse && huge) {
    IdleBlocks& blocks = idle_blocks();
    const std::lock_guard lock(blocks.mutex);
    try {
      blocks.live.emplace(p, rounded);
    } catch (...) {
      std::free(p);
      throw;
    }
  }
  return p;
}

void free_large(void* p) noexcept {
  if (reuse && p != nullptr) {
    IdleBlocks& blocks = idle_blocks();
    const std::lock_guard lock(blocks.mutex);
    const auto it = blocks.live.find(p);
    if (it != blocks.live.end()) {
      const std::size_t size = it->second;
      blocks.live.erase(it);
      if (size <= max_idle_large_bytes) {
        // Room by freeing the smallest idle blocks: the large ones are the expensive ones.
        while (blocks.idle_bytes + size > max_idle_large_bytes) {
          const auto smallest = blocks.idle.begin();
          blocks.idle_bytes -= smallest->first;
          std::free(smallest->second);
          blocks.idle.erase(smallest);
        }
        try {
          blocks.idle.emplace(size, p);
          blocks.idle_bytes += size;
          return;
        } catch (...) {
          // No room for the entry: free the block instead.
        }
      }
    }
  }
  std::free(p);
}

}  // namespace shadowcts
