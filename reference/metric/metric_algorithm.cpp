#include "reference/metric/metric_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/metric/metric_shadows.h"

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

  AlgorithmOutput run(const Case& c, const ViewSamples& samples,
                      const std::string& variant) const override {
    AlgorithmOutput output =
        metric::run_metric(c, samples, metric::parse_metric_variant(variant)).output;
    output.counters.push_back({"light_on_caster_samples",
                               shadow_samples_by_light_on_caster(c, samples, output.shadowed)});
    return output;
  }

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_metric() {
  return std::make_unique<MetricAlgorithm>();
}

}  // namespace shadowcts
