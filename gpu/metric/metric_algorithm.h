#pragma once
// The `metric` Algorithm of the CUDA backends, one for each build of the traversal kernel: the
// device (`cuda`) and the emulator (`cuda-emu`). Both run the same host pipeline
// (metric_shadows.h).
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_backend.h"
#include "gpu/metric/metric_shadows.h"
#include "shadowcts/algorithm.h"

namespace shadowcts {

struct MetricKernelBackend : KernelBackend {
  gpu_metric::KernelRunner run_kernel = nullptr;
};

// id "metric", variants "capsules", "spheres", "capsules16"; phases clustering, build, query;
// counters as the reference's plus near_threshold_samples, stack_overflow_samples and
// exact_test_samples (the samples the kernel handed to the host, by reason).
std::unique_ptr<Algorithm> make_metric_kernel_algorithm(MetricKernelBackend backend);

// Backend "cuda-emu": the kernel run by the CUDA-subset emulator (gpu/emulator) on the host, on
// every machine; its records carry an `emulated_threads` counter.
std::unique_ptr<Algorithm> make_metric_cuda_emu();

// Backend "cuda": the kernel on the device, NotSupported without one. Defined in shadowcts_gpu
// (built only where nvcc exists).
std::unique_ptr<Algorithm> make_metric_cuda();

}  // namespace shadowcts
