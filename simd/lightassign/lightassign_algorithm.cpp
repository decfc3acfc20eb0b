#include "simd/lightassign/lightassign_algorithm.h"

#include <optional>
#include <stdexcept>
#include <string>

#include "reference/lightassign/clustered_assignment.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "shadowcts/phase_clock.h"
#include "simd/lightassign/clustered_assignment.h"
#include "simd/lightassign/tiled_assignment.h"

namespace shadowcts {
namespace {

class SimdLightAssign final : public Algorithm {
 public:
  SimdLightAssign() : reference_(make_lightassign()) {
    info_.id = "lightassign";
    info_.backend = "simd";
    info_.variants = {"tiled", "clustered", "clustered+eb", "clustered+en", "clustered+nk3"};
    info_.summary =
        "tiled and clustered light assignment on Highway lanes (32 BVH children or light "
        "candidates per list volume) and oneTBB (lists in parallel); the reference's lists";
    info_.capabilities.output = OutputKind::light_lists;
    info_.capabilities.ranged_lights = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  // The reference's reasons (sample behind the camera, key bits, light count), for the same
  // variant names.
  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    return reference_->unsupported_reason(c, samples, variant);
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    const ViewSamples& samples = scene.view_samples;
    if (samples.samples.size() != std::size_t(samples.width) * samples.height)
      throw std::invalid_argument("lightassign: sample count is not width x height");
    if (variant == "tiled") return simd::assign_lights_tiled(scene, lightassign_tile_size);
    if (const auto settings = clustered_settings(variant))
      return simd::assign_lights_clustered(scene, *settings);
    throw std::invalid_argument("lightassign: unknown variant '" + variant + "'");
  }

 private:
  std::unique_ptr<Algorithm> reference_;
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_lightassign() {
  return std::make_unique<SimdLightAssign>();
}

}  // namespace shadowcts
