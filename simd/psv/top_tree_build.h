#pragma once
// The TOP tree of reference/psv built on oneTBB, node for node the reference's tree.
//
// The reference inserts triangles one at a time in a seeded random order, and a triangle's path
// depends on every volume inserted before it. Here the triangles are inserted in batches: every
// triangle of a batch descends the tree as it stood before the batch, in parallel, and the batch
// is then committed in insertion order. An earlier triangle of the same batch can only have
// filled the leaf a later one reached (a leaf is replaced, nothing above it changes), so the later
// one resumes its descent from the volume now standing in that leaf, with the same parent and
// ancestor as the reference's uninterrupted descent. Batches grow with the tree (half its
// volumes), which keeps those resumed descents short. The depths, wedges and height, which the
// reference updates along each path, are computed after the last batch from the finished tree,
// with the reference's own order of comparisons, so every bit agrees.
#include <cstdint>
#include <vector>

#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_build.h"
#include "shadowcts/case.h"
#include "simd/psv/plane_side.h"

namespace shadowcts::simd::psv {

// How the parallel build went (not counters of the algorithm: they describe this port's work).
struct BuildWork {
  std::uint64_t batches = 0;
  std::uint64_t resumed_descents = 0;  // triangles whose leaf an earlier one of the batch filled
};

// ref::insertion_order with the light sides decided in parallel: the same order and statistics.
std::vector<std::uint32_t> insertion_order(const Case& c, const ref::PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           std::uint64_t seed, ref::BuildStatistics& statistics);

// ref::build_top_tree in parallel batches: the same tree, sources and statistics. `corners`
// receives the corners of every volume, for the queries.
ref::TopTree build_top_tree(const Case& c, const PlaneSide& planes,
                            const std::vector<std::uint32_t>& order,
                            ref::BuildStatistics& statistics, std::vector<VolumeCorners>& corners,
                            BuildWork& work);

}  // namespace shadowcts::simd::psv
