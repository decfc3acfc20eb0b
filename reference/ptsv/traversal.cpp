#include "reference/ptsv/traversal.h"

#include <bit>

namespace shadowcts::ptsv {

ClusterTraversal::ClusterTraversal(ClusterHierarchy& hierarchy, const ViewFrame& frame,
                                   const ViewSamples& samples, const ReceiverRule& rule,
                                   NodeBounds bounds, bool extra_planes,
                                   const NodeTolerances& tolerances,
                                   std::vector<std::uint8_t>& shadowed, TraversalCounters& counters)
    : hierarchy_(hierarchy),
      frame_(frame),
      samples_(samples),
      rule_(rule),
      bounds_(bounds),
      culling_(extra_planes ? CullingPlanes::extra : CullingPlanes::none),
      tolerances_(tolerances),
      shadowed_(shadowed),
      counters_(counters) {}

void ClusterTraversal::traverse_from_root(const ShadowVolume& volume) {
  traverse_node(volume, 0, 0, hierarchy_.child_mask(0, 0));
}

void ClusterTraversal::traverse_from(const ShadowVolume& volume, int level, std::uint32_t node) {
  const int saved_level = job_level_;
  job_level_ = -1;  // a job is finished, never re-emitted
  traverse_node(volume, level, node, hierarchy_.child_mask(level, node));
  job_level_ = saved_level;
}

void ClusterTraversal::emit_jobs_at(int level, std::uint32_t volume_index,
                                    std::vector<TraversalJob>* jobs) {
  job_level_ = level;
  job_volume_ = volume_index;
  jobs_ = jobs;
}

NodeVerdict ClusterTraversal::test_child(const ShadowVolume& volume, int child_level,
                                         std::uint32_t child) {
  // Looked up only for a node the planes accept; a node without samples has none to lose.
  const auto reach = [&] {
    const std::ptrdiff_t at = hierarchy_.find(child_level, child);
    return at < 0 ? 0.0 : hierarchy_.level(child_level).reject_reach[std::size_t(at)];
  };
  if (bounds_ == NodeBounds::explicit_boxes)
    return classify_node(volume, hierarchy_.bounds(child_level, child), tolerances_, culling_,
                         counters_, reach);
  // CLIPSPACETRPOINT / CLIPSPACETAPOINT from the key: the cell's corners.
  const FrustumCell cell = implicit_node_cell(hierarchy_.layout(), child_level, child);
  return classify_node(volume, cell_corners(frame_, cell), tolerances_, culling_, counters_, reach);
}

void ClusterTraversal::traverse_node(const ShadowVolume& volume, int level, std::uint32_t node,
                                     std::uint32_t child_mask) {
  if (level == job_level_) {
    jobs_->push_back({job_volume_, node});
    ++counters_.first_pass_jobs;
    return;
  }
  ++counters_.nodes_visited;
  if (level == hierarchy_.leaf_level()) {
    test_view_samples(volume, node);
    return;
  }
  // The 32 lanes: each tests one existing child (lines 7-19), then BALLOT gathers the results.
  std::uint32_t intersected = 0, accepted = 0;
  for (std::uint32_t lane = 0; lane < 32; ++lane) {
    if ((child_mask & (1u << lane)) == 0) continue;
    const NodeVerdict verdict = test_child(volume, level + 1, (node << fanout_bits) | lane);
    if (verdict == NodeVerdict::accept) accepted |= 1u << lane;
    if (verdict == NodeVerdict::refine) intersected |= 1u << lane;
  }
  if (accepted != 0) hierarchy_.clear_children(level, node, accepted);  // ATOMICAND, line 24
  std::uint32_t remaining = intersected & ~accepted & child_mask;
  while (remaining != 0) {
    const std::uint32_t next = 31u - std::uint32_t(std::countl_zero(remaining));
    const std::uint32_t next_node = (node << fanout_bits) | next;
    const std::uint32_t next_mask =
        level + 1 < hierarchy_.leaf_level() ? hierarchy_.child_mask(level + 1, next_node) : 0u;
    traverse_node(volume, level + 1, next_node, next_mask);
    remaining &= ~(1u << next);
  }
}

void ClusterTraversal::test_view_samples(const ShadowVolume& volume, std::uint32_t key) {
  // The leaf does not know which of the tile's samples are in this cluster: all are tested.
  const ClusterCoordinate c = hierarchy_.layout().deinterleave(key);
  for (const std::uint32_t* s = hierarchy_.tile_begin(c.x, c.y); s != hierarchy_.tile_end(c.x, c.y);
       ++s) {
    ++counters_.sample_tests;
    const ViewSample& sample = samples_.samples[*s];
    if (sample_in_volume(volume, sample) && !shadowed_[*s] && rule_.caster_counts(volume, sample))
      shadowed_[*s] = 1;
  }
}

void ClusterTraversal::mark_trivially_accepted(const std::vector<std::uint32_t>& keys) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (keys[i] != no_key && !hierarchy_.path_intact(keys[i])) shadowed_[i] = 1;
}

}  // namespace shadowcts::ptsv
