#pragma once
// The reference's unique clusters (reference/lightassign/unique_clusters.h: same ids, keys, tiles,
// members and order) found tile by tile in parallel: the samples of a screen tile are its pixels
// in ascending index (the by-tile order of the reference's stable counting sort), so every tile
// gathers, sorts and compacts its own (key, sample) pairs without a serial pass over the samples.
#include <cstdint>
#include <vector>

#include "reference/lightassign/unique_clusters.h"

namespace shadowcts::simd {

// pixel_key[s] for every view sample s = y * width + x; clustered[s] != 0 for the samples that
// have a cluster (the regular ones).
UniqueClusters find_unique_clusters(const std::vector<std::uint32_t>& pixel_key,
                                    const std::vector<std::uint8_t>& clustered, std::uint32_t width,
                                    std::uint32_t height, std::uint32_t tile_size);

}  // namespace shadowcts::simd
