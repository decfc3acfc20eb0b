#pragma once
// The reference `lightassign`: tiled (Paper I) and clustered (Paper II) light assignment, and the
// per-sample exact lists. Variants:
//   tiled          32x32 tiles, per-tile min/max depth sub-frusta, per-light tile insertion
//   clustered      tile x exponential depth slice, implicit bounds, 32-wide light BVH
//   clustered+eb   explicit bounds (AABB of the cluster's samples)
//   clustered+en   explicit normal cones with the back-face rule
//   clustered+nk3  normal clustering, 3x3 cells per cube face, implicit cones
//   brute          per-sample exact sets (optimal efficiency)
// Counters: see light_assignment_counters() in light_list_builder.h.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reference/lightassign/clustered_assignment.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {

// Paper I's tile size, also Paper II's screen-space tiling of the clusters.
inline constexpr std::uint32_t lightassign_tile_size = 32;

// The settings of a clustered variant; nullopt for a variant that is not clustered. Every
// backend of lightassign reads its variants from here.
std::optional<ClusteredSettings> clustered_settings(const std::string& variant);

// The shell of every lightassign backend. Its variants: lightassign_variants() (or some of them);
// a variant's configuration is its clustered_settings().
class LightAssignAlgorithm : public VariantTableAlgorithm<std::optional<ClusteredSettings>> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 protected:
  // The case's ranged lights must fit the lists' indices; but for brute, every regular sample
  // must lie in front of the eye (tiles and slices), tiled's in their own pixels, and clustered
  // keys must fit their bits.
  std::optional<std::string> input_problem(const Case& c, const ViewSamples& samples,
                                           const Variant& variant) const override;
};

// The reference's variants, in order; brute has no structure to build, so no phases.
std::vector<AlgorithmVariant<std::optional<ClusteredSettings>>> lightassign_variants();

// id "lightassign", backend "reference", output light_lists, capability ranged_lights.
std::unique_ptr<Algorithm> make_lightassign();

}  // namespace shadowcts
