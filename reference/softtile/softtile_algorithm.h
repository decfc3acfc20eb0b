#pragma once
// Reference `softtile`: tiled per-triangle soft shadow volumes after Kalbertodt (2023, the post in
// ../shared/papers/): a gather pass culls the scene for the frame; an eval pass per 16 x 16 pixel
// tile bounds the tile's relevant samples by a sphere or a tapered capsule, culls cluster cones
// then truncated triangle cones against it, and rasterizes every candidate into each pixel's disk
// bitmask (the 16 x 16 grid or N x 31 rows), optionally rotated per pixel. The visible fraction is
// the share of the disk's cells left lit.
//
// The tile's candidate buffer holds tile_triangle_limit triangles, as the post's shared memory
// does; a tile with more is not dropped (the post's checkerboard) but processed in further batches,
// and counted. The counters are listed in reference/softtile/counters.h.
#include <memory>
#include <string>
#include <vector>

#include "reference/softtile/softtile_variant.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {

inline constexpr int softtile_tile_size = 16;
inline constexpr std::size_t softtile_tile_triangle_limit = 2048;

// id "softtile", backend "reference", output soft_shadow, sun disks only. Variants: grid16
// (default), grid16+rot, rows3, rows5, rows7, rows15, rows31, rows31+rot, post.
std::unique_ptr<Algorithm> make_softtile();

// The error budget each variant declares (docs/soft-shadow-budgets.md). Throws
// std::invalid_argument for an unknown variant.
SoftErrorBudget softtile_error_budget(const std::string& variant);

// The variants every softtile backend registers some of: softtile::variant_names(), each with its
// softtile::parse_variant() and softtile_error_budget().
std::vector<AlgorithmVariant<softtile::Variant>> softtile_variants();

}  // namespace shadowcts
