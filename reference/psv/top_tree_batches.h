#pragma once
// The reference's TOP tree (top_tree_build.h), node for node, from batches of descents: how the
// ports build it in parallel (simd on oneTBB threads, cuda on the device) and still build the
// reference's tree.
//
// The reference inserts triangles one at a time in a seeded random order, and a triangle's path
// depends on every volume inserted before it. Here every triangle of a batch descends the tree as
// it stood before the batch (the engine's work, in parallel), and the batch is then committed in
// insertion order. An earlier triangle of the same batch can only have filled the empty child a
// later one reached (a child is filled, nothing above it changes), so the later one resumes its
// descent from the volume now standing there, with the same parent and ancestor as the
// reference's uninterrupted descent. Batches grow with the tree (half its volumes, at most 32768),
// which keeps those resumed descents short. The depths and wedges, which the reference updates
// along each path, are computed from the finished tree with the reference's own order of
// comparisons, so every bit agrees; the height as each volume is committed (nodes never move).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_build.h"
#include "shadowcts/case.h"
#include "shadowcts/huge_pages.h"

namespace shadowcts::psv {

// Where a triangle's descent stopped: the node whose empty child it fills (which child, and the
// innermost intersection node above it), or a shadow leaf (dropped).
struct Descent {
  std::uint32_t parent = no_node;
  std::uint32_t ancestor = no_node;
  bool into_intersection = false;
  bool dropped = false;
};

// What a triangle of a batch brings to its commit unless it was dropped: its volume's depth,
// nodes and source.
struct BatchVolume {
  float depth = 0.0f;
  TopNode nodes[nodes_per_volume];
  VolumeSource source;
};

// A batch's volumes (4.6 MB at the largest batch), in huge pages: a fresh 4 KiB page costs a
// fault (huge_pages.h).
using BatchVolumes = HugePageVector<BatchVolume>;

// The volume of `triangle` (an index into planes.triangles()), as the reference makes it.
void make_batch_volume(const PlaneSide& planes, std::uint32_t triangle, BatchVolume& volume);

// make_batch_volume for every triangle of a batch that was not dropped, on oneTBB threads.
void make_batch_volumes(const PlaneSide& planes, const std::vector<std::uint32_t>& triangles,
                        const std::vector<Descent>& descents, BatchVolumes& volumes);

// What descends: a port's plane tests and parallelism.
class DescentEngine {
 public:
  virtual ~DescentEngine() = default;
  // Descends each triangle of `triangles` (indices into the case's triangles) from the root of
  // `tree`, which does not change during the call, into out[i], and makes volumes[i] of each
  // triangle not dropped (make_batch_volume; after the descents, make_batch_volumes).
  virtual void descend_batch(const TopTree& tree, const std::vector<std::uint32_t>& triangles,
                             std::vector<Descent>& out, BatchVolumes& volumes) = 0;
  // Continues `d` from `node` on the tree as it stands now (the commit's resumed descents).
  virtual void resume(const TopTree& tree, std::uint32_t node, std::uint32_t triangle,
                      Descent& d) = 0;
};

// One step of the reference's descent (build_top_tree) where the triangle's location at `node`
// is `location` (triangle_location): the next node, or no_node once `d` has reached an empty child
// or a shadow leaf.
inline std::uint32_t step_by_location(const TopTree& tree, std::uint32_t node, int location,
                                      Descent& d) {
  d.parent = node;
  if (location > 0) {
    d.into_intersection = false;
    return tree.nodes[node].positive;
  }
  if (location < 0) {
    if (is_capping_node(node)) {
      d.dropped = true;
      return no_node;
    }
    return node + 1;
  }
  d.into_intersection = true;
  d.ancestor = node;
  return tree.nodes[node].intersection;
}

// One step of the reference's descent with the reference's plane tests.
inline std::uint32_t descend_step(const TopTree& tree, const PlaneSide& planes, std::uint32_t node,
                                  const Triangle& t, Descent& d) {
  return step_by_location(tree, node, triangle_location(tree, planes, node, t), d);
}

struct BatchWork {
  std::uint64_t batches = 0;
  std::uint64_t resumed_descents = 0;  // triangles whose child an earlier one of the batch filled
};

// build_top_tree's tree, sources and statistics, from `engine`'s descents and volumes. The
// depths and wedges are computed on oneTBB threads (the caller's arena).
TopTree build_top_tree_in_batches(const PlaneSide& planes, const std::vector<std::uint32_t>& order,
                                  BuildStatistics& statistics, DescentEngine& engine,
                                  BatchWork& work);

}  // namespace shadowcts::psv
