#include "reference/psv/psv_algorithm.h"

#include <stdexcept>

#include "reference/light_on_caster.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {
namespace {

class PsvAlgorithm final : public Algorithm {
 public:
  PsvAlgorithm() {
    info_.id = "psv";
    info_.backend = "reference";
    info_.variants = psv::psv_variants();
    info_.summary =
        "partitioned shadow volumes: TOP tree with exact plane sides; PSV, D-PSV, D-Stackless "
        "and D-Hybrid queries (Mora 2016)";
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  // build: insertion order and TOP tree; query: the per-sample queries.
  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    psv::PsvOptions options = psv::psv_variant_options(variant);
    options.seed = c.parameters.seed;
    psv::PsvResult result = psv::psv_hard_shadows(c, samples, options);
    AlgorithmOutput output;
    output.shadowed = std::move(result.shadowed);
    output.counters = std::move(result.counters);
    output.phase_ms = std::move(result.phase_ms);
    output.counters.push_back({"light_on_caster_samples",
                               shadow_samples_by_light_on_caster(c, samples, output.shadowed)});
    return output;
  }

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_psv() {
  return std::make_unique<PsvAlgorithm>();
}

}  // namespace shadowcts
