#pragma once
// The reference's unique clusters (reference/lightassign/unique_clusters.h: same ids, keys, tiles,
// members and order) found band by band in parallel: the regular samples are in pixel order, so a
// row of tiles (a band) holds a contiguous run of them, and within a band each tile's samples in
// pixel order are the by-tile order of the reference's stable counting sort. Every tile sorts its
// (key, sample) pairs by a counting sort on the key (stable: the reference's std::sort order of
// the pairs) and compacts them, without a serial pass over the samples.
#include <cstdint>
#include <vector>

#include "reference/lightassign/unique_clusters.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"
#include "simd/lightassign/uninitialized_vector.h"

namespace shadowcts::simd {

// Where each pixel row's regular samples start: row y holds regular samples
// [start[y], start[y + 1]) (the regular samples are in pixel order); height + 1 entries.
std::vector<std::uint32_t> regular_rows(const RegularSamples& regular, std::uint32_t width,
                                        std::uint32_t height);

// key[i]: the cluster key of regular sample i; view_samples: width x height, the size of
// cluster_of_sample. member_regular receives the regular index of every member (the order of
// members), for reading the members' positions and normals as arrays; `members` (the view sample
// indices) is filled only when with_members.
UniqueClusters find_unique_clusters(const RegularSamples& regular, const std::uint32_t* key,
                                    std::uint32_t width, std::uint32_t height,
                                    std::uint32_t tile_size,
                                    UninitializedVector<std::uint32_t>& member_regular,
                                    bool with_members = true);

// grow_to_contain (reference/lightassign/view_frustum.h) of `box` by the positions of regular
// samples first..last in order, returning how many grew it; members whose box lies inside `box`
// (the usual case for an implicit box) cannot grow it, which one min/max pass shows without the
// sequence.
std::uint32_t grow_to_contain_all(Aabb& box, const RegularSamples& regular,
                                  const std::uint32_t* first, const std::uint32_t* last);

}  // namespace shadowcts::simd
