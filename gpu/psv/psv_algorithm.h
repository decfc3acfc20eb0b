#pragma once
// `psv` on CUDA: the reference's TOP tree (built on the host, uploaded) queried by one device
// thread per sample with the variant's query: stack32 (PSV), depth (D-PSV), stackless
// (D-Stackless) and hybrid (D-Hybrid), as the reference defines them (psv::psv_variant_options).
// Two builds of the same kernel source: `cuda` on a device (NotSupported without one) and
// `cuda-emu`, run by the CUDA-subset emulator on the host on every machine; the emulated records
// carry an `emulated_threads` counter.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "psv", backend "cuda-emu"; counters as the reference plus "emulated_threads".
std::unique_ptr<Algorithm> make_psv_cuda_emu();

// id "psv", backend "cuda"; only in builds with CUDA (shadowcts_gpu, SHADOWCTS_HAVE_CUDA).
std::unique_ptr<Algorithm> make_psv_cuda();

}  // namespace shadowcts
