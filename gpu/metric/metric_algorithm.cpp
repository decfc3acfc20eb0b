#include "gpu/metric/metric_algorithm.h"

#include <utility>

#include "reference/light_on_caster.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

// The clustering is the per-model precomputation of the paper (non-deformable models): timed as
// its own phase, apart from the per-frame build and query.
constexpr const char* clustering_phase = "clustering";

class MetricKernelAlgorithm final : public VariantTableAlgorithm<gpu_metric::GpuMetricOptions> {
 public:
  explicit MetricKernelAlgorithm(MetricKernelBackend backend)
      : VariantTableAlgorithm(
            backend.describe("metric", point_and_directional_hard_shadows),
            variant_table({"capsules", "spheres", "capsules16"},
                          gpu_metric::parse_gpu_metric_variant,
                          {.phases = {clustering_phase, build_phase, query_phase}})),
        backend_(std::move(backend)) {}

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    gpu_metric::GpuMetricRun run =
        gpu_metric::run_metric(scene, variant.config, backend_.run_kernel);
    run.output.phase_ms = {{clustering_phase, 1e3 * run.clustering_seconds},
                           {build_phase, 1e3 * run.build_seconds},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(scene.source, scene.view_samples, run.output.shadowed)});
    if (backend_.emulated) run.output.counters.push_back({"emulated_threads", run.kernel_threads});
    return std::move(run.output);
  }

  MetricKernelBackend backend_;
};

}  // namespace

std::unique_ptr<Algorithm> make_metric_kernel_algorithm(MetricKernelBackend backend) {
  return std::make_unique<MetricKernelAlgorithm>(std::move(backend));
}

std::unique_ptr<Algorithm> make_metric_cuda_emu() {
  MetricKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's metric traversal kernel EMULATED on the host (gpu/emulator: a fiber per "
      "CUDA thread, no GPU involved); the reference's clusters and tree, uploaded";
  backend.run_kernel = gpu_metric::run_metric_traversal_kernel_emulated;
  backend.emulated = true;
  return make_metric_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
