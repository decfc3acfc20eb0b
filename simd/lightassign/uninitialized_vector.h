#pragma once
// A std::vector whose resize leaves new elements unset, for the simd lightassign's large arrays
// that are written in full right after (zeroing them first would be a wasted, serial pass over
// memory: a resize's value-initialization runs on one thread, the writes that follow in parallel).
// Its memory comes from oneTBB's scalable allocator, which keeps freed large blocks for the next
// call instead of handing them back to the system: a call then writes pages it has used before
// rather than fresh ones the kernel must zero (the first call of a process still pays for them).
#include <new>
#include <utility>
#include <vector>

#include <tbb/scalable_allocator.h>

namespace shadowcts::simd {

// An allocator that leaves a value-constructed element unset (other constructions as usual).
template <class T>
struct Uninitialized : tbb::scalable_allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = Uninitialized<U>;
  };
  Uninitialized() = default;
  template <class U>
  Uninitialized(const Uninitialized<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using UninitializedVector = std::vector<T, Uninitialized<T>>;

}  // namespace shadowcts::simd
