#pragma once
// Runs work on at most a given number of oneTBB threads.
#include <cstdint>

#include <tbb/task_arena.h>

namespace shadowcts {

// Runs f() inside an arena of `threads` threads (0: all hardware threads); every oneTBB
// algorithm f starts runs there.
template <class F>
void run_with_thread_limit(std::uint32_t threads, F&& f) {
  tbb::task_arena arena(threads == 0 ? int(tbb::task_arena::automatic) : int(threads));
  arena.execute(f);
}

}  // namespace shadowcts
