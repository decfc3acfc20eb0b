#pragma once
// Work counters of `softtile`, in the order every backend reports them: gather_clusters,
// gather_clusters_culled, gather_triangles, gather_light_facing_dropped, tiles,
// tiles_with_relevant_pixels, tile_capsule_bounds, tile_candidates_total, tile_candidates_max,
// overflowing_tiles, overflow_batches, pixel_triangle_tests, triangles_rasterized,
// triangles_rasterized_max_per_pixel. All are sums and maxima of per-tile integers, so they do not
// depend on how the tiles are spread over threads or blocks.
#include <cstdint>
#include <span>

#include "reference/softtile/softtile_gather.h"
#include "shadowcts/algorithm.h"

namespace shadowcts::softtile {

// What one screen tile did.
struct TileCounters {
  bool relevant = false;             // it has samples to shade
  bool capsule = false;              // bounded by a tapered capsule (else by a sphere)
  std::uint64_t candidates = 0;      // the length of its caster list
  std::uint64_t tests = 0;           // pixel-triangle tests, summed over its pixels
  std::uint64_t rasterized = 0;      // triangles rasterized, summed over its pixels
  std::uint64_t rasterized_max = 0;  // the most triangles rasterized into one of its pixels
};

// The gather's counts, then the tiles' sums and maxima. A list longer than the tile's buffer of
// softtile_tile_triangle_limit triangles counts as an overflowing tile and takes
// (length - 1) / limit further batches.
Counters to_counters(const Gathered& gathered, std::span<const TileCounters> tiles);

}  // namespace shadowcts::softtile
