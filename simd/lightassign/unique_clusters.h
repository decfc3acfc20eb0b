#pragma once
// The reference's unique clusters (reference/lightassign/unique_clusters.h: same ids, keys, tiles,
// members and order) found band by band in parallel: the regular samples are in pixel order, so a
// row of tiles (a band) holds a contiguous run of them, and within a band each tile's samples in
// pixel order are the by-tile order of the reference's stable counting sort. Every tile sorts its
// (key, sample) pairs by a counting sort on the key (stable: the reference's std::sort order of
// the pairs) and compacts them, without a serial pass over the samples.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/unique_clusters.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"
#include "simd/lightassign/lightassign_kernels.h"
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

// The clustered variants' per-sample work in one pass over each band of tile rows (the bands in
// parallel): every regular sample's cluster key (row_cluster_keys, the normal cell or'ed in when
// the grid has normal divisions), the band's distinct keys (a hash map from key to slot) with their
// member counts and the box of their members' positions, then, once every band's count is known,
// the clusters in the reference's order (by tile, then key: a band's slots sorted by key, since a
// key holds its tile column above its slice and normal), each sample's cluster and the members.
struct SampleClusters {
  UniqueClusters clusters;  // as find_unique_clusters, without `members`
  // Per cluster: the box of its members' positions, as grow_to_contain grows it from the first
  // member in member order (the first of equal values is kept).
  std::vector<glm::vec3> low, high;
  double deepest = 0.0;  // std::max over 0 and every sample's view depth
};

SampleClusters cluster_samples(const RegularSamples& regular, const ViewFrame& frame,
                               const ClusterGrid& grid, std::uint32_t width, std::uint32_t height);

// The regular index of every member of cluster_samples' clusters, in the order of members (by
// cluster, each in pixel order), band by band in parallel. Only the variants that read members
// (explicit normal cones, implicit bounds that some member grows) ask for them.
UninitializedVector<std::uint32_t> cluster_members(const UniqueClusters& clusters,
                                                   const RegularSamples& regular,
                                                   std::uint32_t width, std::uint32_t height,
                                                   std::uint32_t tile_size);

// Whether `box` holds the box (low, high) (false for NaN).
inline bool box_holds(const Aabb& box, const glm::vec3& low, const glm::vec3& high) {
  return box.min.x <= low.x && box.min.y <= low.y && box.min.z <= low.z && high.x <= box.max.x &&
         high.y <= box.max.y && high.z <= box.max.z;
}

// grow_to_contain (reference/lightassign/view_frustum.h) of `box` by the positions of regular
// samples first..last in order, returning how many grew it; members whose box lies inside `box`
// (the usual case for an implicit box) cannot grow it, which one min/max pass shows without the
// sequence.
std::uint32_t grow_to_contain_all(Aabb& box, const RegularSamples& regular,
                                  const std::uint32_t* first, const std::uint32_t* last);
// The same, given the box of those positions (low, high).
std::uint32_t grow_to_contain_all(Aabb& box, const glm::vec3& low, const glm::vec3& high,
                                  const RegularSamples& regular, const std::uint32_t* first,
                                  const std::uint32_t* last);

}  // namespace shadowcts::simd
