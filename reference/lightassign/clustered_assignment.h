#pragma once
// Clustered light assignment (Paper II): cluster keys from tile (i, j), exponential depth slice k
// and optionally the quantized normal; unique clusters by local sorting and compaction; implicit
// bounds from the key (the tile x slice sub-frustum) or explicit bounds from the samples (Eb);
// optional normal cones, implicit from the normal cell (Nk) or explicit from the samples (En),
// with the back-face rule; lights found per cluster by depth-first traversal of the 32-wide
// light BVH, the leaves decided by the exact sphere/box predicate.
#include <cstdint>

#include "shadowcts/algorithm.h"

namespace shadowcts {

struct ClusteredSettings {
  std::uint32_t tile_size = 32;
  std::uint32_t normal_divisions = 0;  // Nk: X x X cells per cube face; 0: no normal clustering
  bool explicit_bounds = false;        // Eb
  bool explicit_normal_cones = false;  // En
};

AlgorithmOutput assign_lights_clustered(const Case& c, const ViewSamples& samples,
                                        const ClusteredSettings& settings);

}  // namespace shadowcts
