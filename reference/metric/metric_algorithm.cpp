#include "reference/metric/metric_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/metric/metric_shadows.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

class MetricAlgorithm final : public VariantTableAlgorithm<metric::MetricOptions> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // build: clustering, bounding volumes, light-space elements and the metric tree; query: the
  // per-sample traversals. run_metric times its steps itself.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    metric::MetricRun run = metric::run_metric(c, samples, variant.config);
    run.output.phase_ms = {{build_phase, 1e3 * (run.clustering_seconds + run.build_seconds)},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(c, samples, run.output.shadowed)});
    return std::move(run.output);
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_metric() {
  return std::make_unique<MetricAlgorithm>(
      AlgorithmDescription{
          .id = "metric",
          .backend = "reference",
          .summary = "triangle clusters bounded by spheres/capsules, slabs and normal cones; "
                     "ternary metric tree over their light-space cones; watertight triangle tests "
                     "(Deves 2018)",
          .capabilities = point_and_directional_hard_shadows},
      variant_table({"capsules", "spheres", "median", "capsules16"}, metric::parse_metric_variant));
}

}  // namespace shadowcts
