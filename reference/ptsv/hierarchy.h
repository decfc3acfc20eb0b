#pragma once
// The view-sample cluster hierarchy (Sintorn 2014, Section 2 "Building the acceleration
// structure" and 2.1 "Explicit bounds"): levels of 32-bit child masks built from the cluster keys
// (a set bit: that child holds samples), level l's node index being the key shifted right by
// 5 * (levels - l). The paper stores a full tree on the GPU; this reference stores only the nodes
// that exist, sorted by index, with the same masks, so memory follows the samples and not 2^32.
// Each node also carries its explicit bounds: the tight axis-aligned box of its samples, in world
// space (float positions are exact in double, so the box contains them exactly), and the largest
// reject reach of its samples (receiver_rule.h), which decides whether the node may be accepted.
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "reference/ptsv/cluster_keys.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

struct WorldBox {
  glm::dvec3 lo{0.0}, hi{0.0};
};

struct HierarchyLevel {
  std::vector<std::uint32_t> index;       // sorted node indices
  std::vector<std::uint32_t> child_mask;  // bit j: child (index << 5) | j exists (not at leaves)
  std::vector<WorldBox> bounds;           // explicit bounds of each node's samples
  std::vector<double> reject_reach;       // the largest of each node's samples
};

class ClusterHierarchy {
 public:
  // sample_reach: per sample (ReceiverRule::reject_reach).
  ClusterHierarchy(const ClusterKeyLayout& layout, const std::vector<std::uint32_t>& keys,
                   const ViewSamples& samples, const std::vector<double>& sample_reach);

  const ClusterKeyLayout& layout() const { return layout_; }
  int leaf_level() const { return layout_.mask_levels(); }
  const HierarchyLevel& level(int l) const { return levels_[std::size_t(l)]; }

  // Position of node `index` in level l, or -1 when it does not exist.
  std::ptrdiff_t find(int l, std::uint32_t index) const;
  // The node's child mask; 0 for nodes that do not exist.
  std::uint32_t child_mask(int l, std::uint32_t index) const;
  // Clears bits of an existing node's child mask (trivially accepted children, Algorithm 1 l. 24).
  void clear_children(int l, std::uint32_t index, std::uint32_t bits);
  const WorldBox& bounds(int l, std::uint32_t index) const;

  // The regular samples of 8x8 tile (tx, ty), in sample order: what a leaf tests.
  const std::uint32_t* tile_begin(std::uint32_t tx, std::uint32_t ty) const;
  const std::uint32_t* tile_end(std::uint32_t tx, std::uint32_t ty) const;

  // Whether the sample's whole path from the root is still marked as existing; false means some
  // node on it was trivially accepted (the final pass of Section 2, "Traversal").
  bool path_intact(std::uint32_t key) const;

  std::uint64_t node_count() const;

 private:
  ClusterKeyLayout layout_;
  std::vector<HierarchyLevel> levels_;       // 0 .. leaf_level()
  std::vector<std::uint32_t> tile_offsets_;  // CSR over tiles, row-major
  std::vector<std::uint32_t> tile_samples_;
};

}  // namespace shadowcts::ptsv
