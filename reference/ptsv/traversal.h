#pragma once
// Traversal of one shadow volume through the cluster hierarchy (Sintorn 2014, Appendix,
// Algorithm 1), written as the paper's recursion with the warp's 32 lanes as a loop: each
// existing child is tested against the volume; trivially accepted children are recorded by
// clearing their bits in the shared hierarchy (line 24), intersected ones are visited from the
// highest bit down (31 - CLZ, line 27); at the leaf level every sample of the cluster's 8x8 tile
// is tested (TESTVIEWSAMPLES) and, inside the volume, set where the receiver half-space rule
// counts the caster (receiver_rule.h; a node is accepted only where it counts for all its
// samples). The final pass marks the samples whose path from the root lost a bit, i.e. that lie in
// some trivially accepted node.
//
// The hierarchy is shared by all volumes, as in the paper: an accepted node is skipped by every
// later volume. Volumes are processed one after another in triangle order, so the counters are
// deterministic.
#include <cstdint>
#include <vector>

#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/counters.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/triangle_setup.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

enum class NodeBounds {
  implicit_cells,  // the frustum cell a key prefix spans (computed from the key)
  explicit_boxes,  // the tight box of the node's samples (Section 2.1)
};

// A (triangle, node) pair where the first pass of the two-pass traversal stopped (Section 2.2).
struct TraversalJob {
  std::uint32_t volume = 0;  // index into the set-up volumes
  std::uint32_t node = 0;    // node index at the job level
};

class ClusterTraversal {
 public:
  ClusterTraversal(ClusterHierarchy& hierarchy, const ViewFrame& frame, const ViewSamples& samples,
                   const ReceiverRule& rule, NodeBounds bounds, bool extra_planes,
                   const NodeTolerances& tolerances, std::vector<std::uint8_t>& shadowed,
                   TraversalCounters& counters);

  // TRAVERSENODE(SV, 0, 0, root child mask).
  void traverse_from_root(const ShadowVolume& volume);
  // TRAVERSENODE(SV, level, node, its current child mask): the start of a second-pass job.
  void traverse_from(const ShadowVolume& volume, int level, std::uint32_t node);

  // First pass of the two-pass traversal: from now on, reaching a node at `level` records a job
  // (volume_index, node) in `jobs` instead of descending. level < 0 switches it off.
  void emit_jobs_at(int level, std::uint32_t volume_index, std::vector<TraversalJob>* jobs);

  // The final pass: every sample in a trivially accepted node is shadowed.
  void mark_trivially_accepted(const std::vector<std::uint32_t>& keys);

 private:
  void traverse_node(const ShadowVolume& volume, int level, std::uint32_t node,
                     std::uint32_t child_mask);
  NodeVerdict test_child(const ShadowVolume& volume, int child_level, std::uint32_t child);
  void test_view_samples(const ShadowVolume& volume, std::uint32_t key);

  ClusterHierarchy& hierarchy_;
  const ViewFrame& frame_;
  const ViewSamples& samples_;
  const ReceiverRule& rule_;
  NodeBounds bounds_;
  CullingPlanes culling_;
  NodeTolerances tolerances_;
  std::vector<std::uint8_t>& shadowed_;
  TraversalCounters& counters_;
  int job_level_ = -1;
  std::uint32_t job_volume_ = 0;
  std::vector<TraversalJob>* jobs_ = nullptr;
};

}  // namespace shadowcts::ptsv
