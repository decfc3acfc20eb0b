#include "simd/metric/metric_algorithm.h"

#include "reference/light_on_caster.h"
#include "shadowcts/variant_table_algorithm.h"
#include "simd/metric/metric_shadows.h"

namespace shadowcts {
namespace {

// The clustering is the per-model precomputation of the paper (non-deformable models): timed as
// its own phase, apart from the per-frame build and query.
constexpr const char* clustering_phase = "clustering";

class SimdMetricAlgorithm final : public VariantTableAlgorithm<simd::metric::SimdMetricOptions> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    simd::metric::SimdMetricRun run = simd::metric::run_metric(scene, variant.config);
    run.output.phase_ms = {{clustering_phase, 1e3 * run.clustering_seconds},
                           {build_phase, 1e3 * run.build_seconds},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(scene.source, scene.view_samples, run.output.shadowed)});
    return std::move(run.output);
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_metric() {
  return std::make_unique<SimdMetricAlgorithm>(
      AlgorithmDescription{
          .id = "metric",
          .backend = "simd",
          .summary = "metric on Highway + oneTBB: the reference's clusters, the same ternary "
                     "metric tree built in parallel, 8x8-sample packets in vector lanes (Deves "
                     "2018)",
          .capabilities = point_and_directional_hard_shadows},
      variant_table({"capsules", "spheres", "capsules16"}, simd::metric::parse_simd_metric_variant,
                    {.phases = {clustering_phase, build_phase, query_phase}}));
}

}  // namespace shadowcts
