#pragma once
// The TOP tree of partitioned shadow volumes (Gerhards et al. 2015; Mora et al. 2016), in the
// memory layout of Mora 2016, section 3.6: an array of 32-byte nodes, one shadow volume as four
// consecutive nodes (three edge planes through the light, then the triangle's capping plane).
//
// Every node plane is oriented so that the volume lies on its negative side. The negative child of
// node 4v + k is node 4v + k + 1 for k < 3 (never stored), and the negative child of the capping
// node is the "shadow" leaf: a point there is inside the volume. Positive and intersection
// children are either no_node (a lit or empty leaf) or the first node of another volume. The two
// per-volume values of the 2016 paper, the depth and the ancestor link, are stored once per volume
// in the word the implicit negative child frees in nodes 0 and 1; node 2 keeps the triangle.
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "shadowcts/huge_pages.h"

namespace shadowcts::psv {

inline constexpr std::uint32_t no_node = std::numeric_limits<std::uint32_t>::max();
inline constexpr std::uint32_t nodes_per_volume = 4;
inline constexpr std::uint32_t capping_plane = 3;  // position of the capping node in its volume

struct TopNode {
  // a x + b y + c z + d, rounded to float from the double-precision plane; negative inside.
  std::array<float, 4> plane{};
  std::uint32_t positive = no_node;
  std::uint32_t intersection = no_node;
  // Wedge of the intersection subtree (wedge optimization of Gerhards et al. 2015): an upper
  // bound on |plane(p)| for points p in the shadow volume of any triangle below `intersection`,
  // per unit of light distance for a point light, absolute for a directional light. Infinite on
  // capping nodes, whose plane does not contain the light.
  float wedge = 0.0f;
  // Per-volume word: node 0 the depth (float bits), node 1 the ancestor link, node 2 the triangle
  // index, node 3 unused (0).
  std::uint32_t volume_word = 0;
};
static_assert(sizeof(TopNode) == 32, "the 2016 paper's node is 32 bytes");

// How the exact fallback of a plane test recomputes the plane from the triangle: the edge's two
// vertex indices (0..2) in canonical order and the orientation sign of each of the four planes.
struct VolumeSource {
  std::array<std::array<std::uint8_t, 2>, 3> edge{};
  std::array<std::int8_t, 4> orientation{};
};

struct TopTree {
  HugePageVector<TopNode> nodes;         // volume v: nodes[4 v .. 4 v + 3]; 128 MB at 1M triangles
  HugePageVector<VolumeSource> sources;  // per volume
  std::uint32_t root = no_node;          // 0 once a volume exists
};

inline std::uint32_t volume_of(std::uint32_t node) {
  return node / nodes_per_volume;
}
inline std::uint32_t first_node(std::uint32_t node) {
  return node - node % nodes_per_volume;
}
inline bool is_capping_node(std::uint32_t node) {
  return node % nodes_per_volume == capping_plane;
}

// Depth of the volume: the smallest light distance of the triangles in the subtree of its first
// node (a lower bound, rounded down).
inline float volume_depth(const TopTree& tree, std::uint32_t node) {
  return std::bit_cast<float>(tree.nodes[first_node(node)].volume_word);
}
inline void set_volume_depth(TopTree& tree, std::uint32_t node, float depth) {
  tree.nodes[first_node(node)].volume_word = std::bit_cast<std::uint32_t>(depth);
}
// The node whose intersection subtree holds the volume, innermost; no_node at the top level.
inline std::uint32_t ancestor_link(const TopTree& tree, std::uint32_t node) {
  return tree.nodes[first_node(node) + 1].volume_word;
}
inline std::uint32_t volume_triangle(const TopTree& tree, std::uint32_t node) {
  return tree.nodes[first_node(node) + 2].volume_word;
}

}  // namespace shadowcts::psv
