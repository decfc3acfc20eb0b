#include "gpu/metric/metric_algorithm.h"

#include <stdexcept>
#include <utility>

#include "reference/light_on_caster.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {
namespace {

// The clustering is the per-model precomputation of the paper (non-deformable models): timed as
// its own phase, apart from the per-frame build and query.
constexpr const char* clustering_phase = "clustering";

class MetricKernelAlgorithm final : public Algorithm {
 public:
  explicit MetricKernelAlgorithm(MetricKernelBackend backend) : backend_(std::move(backend)) {
    info_.id = "metric";
    info_.backend = backend_.backend;
    info_.variants = {"capsules", "spheres", "capsules16"};
    info_.summary = backend_.summary;
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    if (auto reason = Algorithm::unsupported_reason(c, samples, variant)) return reason;
    return backend_.unavailable_reason ? backend_.unavailable_reason() : std::nullopt;
  }

  std::vector<std::string> timed_phases(const std::string&) const override {
    return {clustering_phase, build_phase, query_phase};
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    if (backend_.unavailable_reason)
      if (auto reason = backend_.unavailable_reason()) throw std::runtime_error(*reason);
    gpu_metric::GpuMetricRun run = gpu_metric::run_metric(
        scene, gpu_metric::parse_gpu_metric_variant(variant), backend_.run_kernel);
    run.output.phase_ms = {{clustering_phase, 1e3 * run.clustering_seconds},
                           {build_phase, 1e3 * run.build_seconds},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(scene.source, scene.view_samples, run.output.shadowed)});
    if (backend_.emulated) run.output.counters.push_back({"emulated_threads", run.kernel_threads});
    return std::move(run.output);
  }

 private:
  MetricKernelBackend backend_;
  AlgorithmInfo info_;
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
