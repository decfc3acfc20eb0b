#pragma once
// The TOP tree as the query kernel reads it (reference/psv/top_tree.h): the uploaded flat array of
// 32-byte nodes (psv_kernels.h), four per shadow volume, and the per-volume words stored in the
// slots the implicit negative children free.
#include <cstdint>
#include <cstring>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/psv_kernels.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

constexpr std::uint32_t nodes_per_volume = 4;
constexpr std::uint32_t capping_plane = 3;  // position of the capping node in its volume

__device__ inline std::uint32_t volume_of(std::uint32_t node) {
  return node / nodes_per_volume;
}
__device__ inline std::uint32_t first_node(std::uint32_t node) {
  return node - node % nodes_per_volume;
}
__device__ inline bool is_capping_node(std::uint32_t node) {
  return node % nodes_per_volume == capping_plane;
}

// Depth of the volume of `node`: a lower bound on the light distance of its subtree's triangles.
__device__ inline float volume_depth(const PsvDeviceNode* nodes, std::uint32_t node) {
  const std::uint32_t bits = nodes[first_node(node)].volume_word;
  float depth;
  std::memcpy(&depth, &bits, sizeof depth);
  return depth;
}
// The node whose intersection subtree holds the volume, innermost; psv_no_node at the top level.
__device__ inline std::uint32_t ancestor_link(const PsvDeviceNode* nodes, std::uint32_t node) {
  return nodes[first_node(node) + 1].volume_word;
}
__device__ inline std::uint32_t volume_triangle(const PsvDeviceNode* nodes, std::uint32_t node) {
  return nodes[first_node(node) + 2].volume_word;
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
