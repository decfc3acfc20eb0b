#pragma once
// The brute-force kernel of the `cuda` backend run by the CUDA-subset emulator (gpu/emulator) on
// the host: the same kernel source, on every machine, with the emulator's checks. Its records say
// backend "cuda-emu" and carry an `emulated_threads` counter: no report can pass it off as a
// device run.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "bruteforce", backend "cuda-emu", variant "float32"; counters as the `cuda` backend plus
// "emulated_threads".
std::unique_ptr<Algorithm> make_bruteforce_hard_shadow_cuda_emu();

}  // namespace shadowcts
