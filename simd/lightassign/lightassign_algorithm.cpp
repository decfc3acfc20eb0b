#include "simd/lightassign/lightassign_algorithm.h"

#include <stdexcept>
#include <string>

#include "reference/lightassign/clustered_assignment.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "simd/lightassign/clustered_assignment.h"
#include "simd/lightassign/tiled_assignment.h"

namespace shadowcts {
namespace {

class SimdLightAssign final : public LightAssignAlgorithm {
 public:
  using LightAssignAlgorithm::LightAssignAlgorithm;

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const ViewSamples& samples = scene.view_samples;
    if (samples.samples.size() != std::size_t(samples.width) * samples.height)
      throw std::invalid_argument("lightassign: sample count is not width x height");
    if (variant.config) return simd::assign_lights_clustered(scene, *variant.config);
    return simd::assign_lights_tiled(scene, lightassign_tile_size);
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_lightassign() {
  return std::make_unique<SimdLightAssign>(
      AlgorithmDescription{
          .id = "lightassign",
          .backend = "simd",
          .summary = "tiled and clustered light assignment on Highway lanes (32 BVH children or "
                     "light candidates per list volume) and oneTBB (lists in parallel); the "
                     "reference's lists",
          .capabilities = {.output = OutputKind::light_lists, .ranged_lights = true}},
      select_variants(lightassign_variants(),
                      {"tiled", "clustered", "clustered+eb", "clustered+en", "clustered+nk3"}));
}

}  // namespace shadowcts
