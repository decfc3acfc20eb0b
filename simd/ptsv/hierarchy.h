#pragma once
// The view-sample cluster hierarchy of the simd ptsv: the reference's nodes (hierarchy.h there),
// built from a parallel sort of (key, sample) pairs instead of one pass per sample, and laid out
// for the lanes: the children of a node are contiguous in the next level (in key order, i.e. by
// bit position), so a node's 32 child bounds are one run of structure-of-arrays loads.
//
// Explicit bounds and reject reach are min/max reductions, which do not depend on the order they
// are taken in, except for the sign of a zero coordinate: the reference keeps the first sample
// (in index order) that reaches the minimum, and so does this build (ties go to the smaller
// sample index), so every box is the reference's bit for bit.
#include <array>
#include <cstdint>
#include <vector>

#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd::ptsv {

namespace ref = ::shadowcts::ptsv;

// Arrays over a level's nodes carry this many zero entries past the last node, so a vector load
// at any node reads only owned memory.
inline constexpr std::size_t lane_padding = 32;

struct Level {
  std::vector<std::uint32_t> index;           // sorted node indices (the key prefixes)
  std::vector<std::uint32_t> child_mask;      // bit j: child (index << 5) | j exists
  std::vector<std::uint32_t> first_child;     // position in the next level of the lowest child
  std::vector<std::uint32_t> parent;          // position in the previous level (0 at the root)
  std::array<std::vector<double>, 3> lo, hi;  // explicit bounds (padded)
  std::vector<double> reach;                  // largest reject reach of the node's samples (padded)
  // Implicit bounds: corner c's coordinate k is corner[c * 3 + k][node] (padded; empty unless
  // built with implicit cells; level 0 never, the root is never tested).
  std::array<std::vector<double>, 24> corner;

  std::size_t size() const { return index.size(); }
};

struct Hierarchy {
  ref::ClusterKeyLayout layout;
  std::vector<Level> levels;  // 0 .. leaf_level()
  int leaf_level() const { return layout.mask_levels(); }

  // Per regular sample: its leaf's position in the leaf level.
  std::vector<std::uint32_t> leaf_of_sample;
  // Per leaf: its 8x8 tile (row-major), whose samples the leaf tests.
  std::vector<std::uint32_t> leaf_tile;
  // Regular samples per tile in sample order (CSR), with what the sample test loads beside them.
  std::vector<std::uint32_t> tile_offsets;
  std::vector<std::uint32_t> tile_sample;       // regular sample index
  std::array<std::vector<double>, 3> tile_pos;  // positions (padded)

  std::uint64_t node_count() const;
};

// keys and reach per regular sample (PreparedScene::samples order); implicit: also the cells'
// corners (ref::implicit_node_cell, ref::cell_corners).
Hierarchy build_hierarchy(const ref::ClusterKeyLayout& layout, const ref::ViewFrame& frame,
                          const PreparedScene& scene, const std::vector<std::uint32_t>& key,
                          const std::vector<double>& reach, bool implicit_cells);

}  // namespace shadowcts::simd::ptsv
