#include "simd/psv/psv_algorithm.h"

#include "reference/light_on_caster.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/phase_clock.h"
#include "simd/psv/psv_shadows.h"

namespace shadowcts {
namespace {

class SimdPsvAlgorithm final : public Algorithm {
 public:
  SimdPsvAlgorithm() {
    info_.id = "psv";
    info_.backend = "simd";
    info_.variants = psv::psv_variants();
    info_.summary =
        "partitioned shadow volumes on oneTBB + Highway: the reference's TOP tree built in "
        "parallel batches, queries in 4x4-pixel packets with node tests in vector lanes; PSV, "
        "D-PSV, D-Stackless, D-Hybrid (Mora 2016)";
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  // build: insertion order and TOP tree; query: the packet queries.
  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    simd::psv::SimdPsvOptions options;
    options.psv = psv::psv_variant_options(variant);
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

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_psv() {
  return std::make_unique<SimdPsvAlgorithm>();
}

}  // namespace shadowcts
