#include "simd/psv/psv_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/variant_table_algorithm.h"
#include "simd/psv/psv_shadows.h"

namespace shadowcts {
namespace {

class SimdPsvAlgorithm final : public VariantTableAlgorithm<psv::PsvOptions> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // build: insertion order and TOP tree; query: the packet queries.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    simd::psv::SimdPsvOptions options;
    options.psv = variant.config;
    options.psv.seed = scene.source.parameters.seed;
    simd::psv::SimdPsvResult result = simd::psv::psv_hard_shadows(scene, options);
    AlgorithmOutput output;
    output.shadowed = std::move(result.shadowed);
    output.counters = std::move(result.counters);
    output.phase_ms = std::move(result.phase_ms);
    output.counters.push_back(
        {"light_on_caster_samples",
         shadow_samples_by_light_on_caster(scene.source, scene.view_samples, output.shadowed)});
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_psv() {
  return std::make_unique<SimdPsvAlgorithm>(
      AlgorithmDescription{
          .id = "psv",
          .backend = "simd",
          .summary = "partitioned shadow volumes on oneTBB + Highway: the reference's TOP tree "
                     "built in parallel batches, queries in 4x4-pixel packets with node tests in "
                     "vector lanes; PSV, D-PSV, D-Stackless, D-Hybrid (Mora 2016)",
          .capabilities = point_and_directional_hard_shadows},
      variant_table(psv::psv_variants(), psv::psv_variant_options));
}

}  // namespace shadowcts
