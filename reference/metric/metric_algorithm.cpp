#include "reference/metric/metric_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/metric/metric_shadows.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {
namespace {

class MetricAlgorithm final : public Algorithm {
 public:
  MetricAlgorithm() {
    info_.id = "metric";
    info_.backend = "reference";
    info_.variants = {"capsules", "spheres", "median", "capsules16"};
    info_.summary =
        "triangle clusters bounded by spheres/capsules, slabs and normal cones; ternary metric "
        "tree over their light-space cones; watertight triangle tests (Deves 2018)";
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  // build: clustering, bounding volumes, light-space elements and the metric tree; query: the
  // per-sample traversals. run_metric times its steps itself.
  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    metric::MetricRun run = metric::run_metric(c, samples, metric::parse_metric_variant(variant));
    run.output.phase_ms = {{build_phase, 1e3 * (run.clustering_seconds + run.build_seconds)},
                           {query_phase, 1e3 * run.traversal_seconds}};
    run.output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(c, samples, run.output.shadowed)});
    return std::move(run.output);
  }

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_metric() {
  return std::make_unique<MetricAlgorithm>();
}

}  // namespace shadowcts
