#include "reference/psv/psv_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

class PsvAlgorithm final : public VariantTableAlgorithm<psv::PsvOptions> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // build: insertion order and TOP tree; query: the per-sample queries.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    psv::PsvOptions options = variant.config;
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
};

}  // namespace

std::unique_ptr<Algorithm> make_psv() {
  return std::make_unique<PsvAlgorithm>(
      AlgorithmDescription{.id = "psv",
                           .backend = "reference",
                           .summary =
                               "partitioned shadow volumes: TOP tree with exact plane sides; "
                               "PSV, D-PSV, D-Stackless and D-Hybrid queries (Mora 2016)",
                           .capabilities = point_and_directional_hard_shadows},
      variant_table(psv::psv_variants(), psv::psv_variant_options));
}

}  // namespace shadowcts
