#include "reference/softtile/counters.h"

#include <algorithm>

#include "reference/softtile/softtile_algorithm.h"

namespace shadowcts::softtile {

Counters to_counters(const Gathered& gathered, std::span<const TileCounters> tiles) {
  std::uint64_t relevant = 0, capsule = 0, candidates = 0, candidates_max = 0, overflowing = 0,
                overflow_batches = 0, tests = 0, rasterized = 0, rasterized_max = 0;
  for (const TileCounters& t : tiles) {
    relevant += t.relevant ? 1 : 0;
    capsule += t.capsule ? 1 : 0;
    candidates += t.candidates;
    candidates_max = std::max(candidates_max, t.candidates);
    overflowing += t.candidates > softtile_tile_triangle_limit ? 1 : 0;
    overflow_batches += t.candidates == 0 ? 0 : (t.candidates - 1) / softtile_tile_triangle_limit;
    tests += t.tests;
    rasterized += t.rasterized;
    rasterized_max = std::max(rasterized_max, t.rasterized_max);
  }
  return {{"gather_clusters", gathered.clusters_in},
          {"gather_clusters_culled", gathered.clusters_culled},
          {"gather_triangles", gathered.triangles.size()},
          {"gather_light_facing_dropped", gathered.light_facing_dropped},
          {"tiles", tiles.size()},
          {"tiles_with_relevant_pixels", relevant},
          {"tile_capsule_bounds", capsule},
          {"tile_candidates_total", candidates},
          {"tile_candidates_max", candidates_max},
          {"overflowing_tiles", overflowing},
          {"overflow_batches", overflow_batches},
          {"pixel_triangle_tests", tests},
          {"triangles_rasterized", rasterized},
          {"triangles_rasterized_max_per_pixel", rasterized_max}};
}

}  // namespace shadowcts::softtile
