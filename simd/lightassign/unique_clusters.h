#pragma once
// The reference's unique clusters (reference/lightassign/unique_clusters.h: same ids, keys, tiles,
// members and order) found tile by tile in parallel: the samples of a screen tile are its pixels
// in ascending index (the by-tile order of the reference's stable counting sort), so every tile
// gathers, sorts and compacts its own (key, sample) pairs without a serial pass over the samples.
#include <cstdint>
#include <vector>

#include "reference/lightassign/unique_clusters.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::simd {

// pixel_key[s] for every view sample s = y * width + x; clustered[s] != 0 for the samples that
// have a cluster (the regular ones).
UniqueClusters find_unique_clusters(const std::vector<std::uint32_t>& pixel_key,
                                    const std::vector<std::uint8_t>& clustered, std::uint32_t width,
                                    std::uint32_t height, std::uint32_t tile_size);

// grow_to_contain (reference/lightassign/view_frustum.h) of `box` by every member's position in
// order, returning how many grew it; members whose box lies inside `box` (the usual case for an
// implicit box) cannot grow it, which one min/max pass shows without the sequence.
std::uint32_t grow_to_contain_all(Aabb& box, const ViewSamples& samples, const std::uint32_t* first,
                                  const std::uint32_t* last);

}  // namespace shadowcts::simd
