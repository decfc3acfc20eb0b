#pragma once
// The `metric` pipeline of the CUDA backends for one prepared scene, the steps of
// reference/metric/metric_shadows.h: the reference's clustering and bounding volumes (the
// per-model precomputation, timed on its own), then per light the reference's light-space
// elements and ternary metric tree, uploaded as the kernel's node records, and the per-sample
// traversal kernel (traversal.cuh). Samples the kernel hands back (a decision within its window,
// a full stack) are walked on the host by the reference's own code.
#include <cstdint>
#include <string>

#include "gpu/metric/traversal.h"
#include "reference/metric/metric_shadows.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::gpu_metric {

struct GpuMetricOptions {
  shadowcts::metric::MetricOptions metric;  // insertion build only
  // Half-width of the band around a threshold where the kernel hands a sample to the host: an
  // angle, or a multiple of S for lengths. 2^-40 lies far above the difference between the
  // device's and the reference's roundings (a few 2^-53 of numbers below 8); tests widen it to
  // send many samples to the host.
  double decision_window = 0x1p-40;
  // Stack entries per thread (MetricInput::stack_limit); tests lower it.
  std::uint32_t stack_limit = stack_capacity;
};

// "capsules", "spheres" and "capsules16" (and the reference's names with another
// max_triangles); throws std::invalid_argument for the median build, which is not ported.
GpuMetricOptions parse_gpu_metric_variant(const std::string& variant);

// The kernel's input from the reference's structures: every tree node in the reference's order
// with its pivot's geometry and thresholds, the clusters' slabs and triangles, the regular samples.
MetricInput metric_kernel_input(const PreparedScene& scene,
                                const shadowcts::metric::ClusteredScene& clustered,
                                const shadowcts::metric::LightStructure& structure,
                                double decision_window);

using KernelRunner = MetricResult (*)(MetricInput);

struct GpuMetricRun {
  AlgorithmOutput output;  // per view sample; the reference's counters plus the hand-backs
  shadowcts::metric::MetricCounters counters;
  std::uint64_t near_threshold_samples = 0;  // a decision within the window
  std::uint64_t stack_overflow_samples = 0;  // more than stack_capacity entries
  std::uint64_t exact_test_samples = 0;      // a float miss beside an edge to decide exactly
  std::uint64_t kernel_threads = 0;          // threads launched
  double clustering_seconds = 0.0;           // clustering and bounding volumes
  double build_seconds = 0.0;                // elements, tree, kernel input
  double traversal_seconds = 0.0;            // kernel (with its uploads) and host hand-backs
};

// On the case's thread limit; deterministic for the case's seed and any thread count. Needs a
// point or directional light.
GpuMetricRun run_metric(const PreparedScene& scene, const GpuMetricOptions& options,
                        KernelRunner run_kernel);

}  // namespace shadowcts::gpu_metric
