#include "reference/lightassign/lightassign_algorithm.h"

#include <stdexcept>
#include <string>

#include "reference/lightassign/brute_assignment.h"
#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/clustered_assignment.h"
#include "reference/lightassign/tiled_assignment.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

class LightAssign final : public LightAssignAlgorithm {
 public:
  using LightAssignAlgorithm::LightAssignAlgorithm;

 private:
  // build: tiles/clusters with their bounds (and cones), clustered: the light BVH; query: the
  // assignment of lights to the lists.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    if (samples.samples.size() != std::size_t(samples.width) * samples.height)
      throw std::invalid_argument("lightassign: sample count is not width x height");
    AlgorithmOutput output;
    run_with_thread_limit(c.parameters.threads, [&] {
      if (variant.config)
        output = assign_lights_clustered(c, samples, *variant.config);
      else if (variant.name == "tiled")
        output = assign_lights_tiled(c, samples, lightassign_tile_size);
      else
        output = assign_lights_brute(c, samples);
    });
    return output;
  }
};

}  // namespace

std::optional<std::string> LightAssignAlgorithm::input_problem(const Case& c,
                                                               const ViewSamples& samples,
                                                               const Variant& variant) const {
  if (c.ranged_lights.size() > 0xFFFFFFFEull) return "more than 2^32 - 2 ranged lights";
  if (variant.name == "brute") return std::nullopt;
  // Tiles and slices need every regular sample in front of the eye.
  const ViewFrustum frustum(c.camera);
  double deepest = 0.0;
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const double d = frustum.depth(glm::dvec3(s.position));
    if (!(d > 0.0))
      return "sample at pixel (" + std::to_string(s.pixel_x) + ", " + std::to_string(s.pixel_y) +
             ") lies behind the camera plane";
    deepest = std::max(deepest, d);
  }
  // Tiled culls by each tile's screen rectangle and sub-frustum (Paper I), which hold a tile's
  // samples only when they lie in their pixels; clustered boxes grow to hold their samples.
  if (variant.name == "tiled")
    if (auto why = sample_outside_its_pixel(c, samples)) return why;
  if (const auto& settings = variant.config) {
    const ClusterGrid grid(c.camera, settings->tile_size, settings->normal_divisions, deepest);
    if (auto why = grid.overflow_reason()) return why;
  }
  return std::nullopt;
}

std::vector<AlgorithmVariant<std::optional<ClusteredSettings>>> lightassign_variants() {
  auto table = variant_table(
      {"tiled", "clustered", "clustered+eb", "clustered+en", "clustered+nk3", "brute"},
      clustered_settings);
  table.back().phases = {};  // brute
  return table;
}

std::unique_ptr<Algorithm> make_lightassign() {
  return std::make_unique<LightAssign>(
      AlgorithmDescription{
          .id = "lightassign",
          .backend = "reference",
          .summary = "tiled (Paper I) and clustered (Paper II) light assignment: tiles with "
                     "min/max depth, exponential depth slices, explicit bounds, normal cones, "
                     "32-wide light BVH; brute: per-sample exact sets",
          .capabilities = {.output = OutputKind::light_lists, .ranged_lights = true}},
      lightassign_variants());
}

std::optional<ClusteredSettings> clustered_settings(const std::string& variant) {
  ClusteredSettings s;
  s.tile_size = lightassign_tile_size;
  if (variant == "clustered") return s;
  if (variant == "clustered+eb") {
    s.explicit_bounds = true;
    return s;
  }
  if (variant == "clustered+en") {
    s.explicit_normal_cones = true;
    return s;
  }
  if (variant == "clustered+nk3") {
    s.normal_divisions = 3;
    return s;
  }
  return std::nullopt;
}

}  // namespace shadowcts
