#include "simd/metric/metric_algorithm.h"

#include "reference/light_on_caster.h"
#include "shadowcts/phase_clock.h"
#include "simd/metric/metric_shadows.h"

namespace shadowcts {
namespace {

// The clustering is the per-model precomputation of the paper (non-deformable models): timed as
// its own phase, apart from the per-frame build and query.
constexpr const char* clustering_phase = "clustering";

class SimdMetricAlgorithm final : public Algorithm {
 public:
  SimdMetricAlgorithm() {
    info_.id = "metric";
    info_.backend = "simd";
    info_.variants = {"capsules", "spheres", "capsules16"};
    info_.summary =
        "metric on Highway + oneTBB: the reference's clusters, the same ternary metric tree "
        "built in parallel, 4x4-sample packets in vector lanes (Deves 2018)";
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  std::vector<std::string> timed_phases(const std::string&) const override {
    return {clustering_phase, build_phase, query_phase};
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    simd::metric::SimdMetricRun run =
        simd::metric::run_metric(scene, simd::metric::parse_simd_metric_variant(variant));
    run.output.phase_ms = {{clustering_phase, 1e3 * run.clustering_seconds},
                           {build_phase, 1e3 * run.build_seconds},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(scene.source, scene.view_samples, run.output.shadowed)});
    return std::move(run.output);
  }

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_metric() {
  return std::make_unique<SimdMetricAlgorithm>();
}

}  // namespace shadowcts
