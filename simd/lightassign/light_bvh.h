#pragma once
// The reference's light BVH (reference/lightassign/light_bvh.h: its definition, built by it) laid
// out for Highway loads: every level's node boxes as structure of arrays, padded to whole nodes of
// 32 with boxes that overlap nothing; the leaves stay in the reference's arrays.
#include <cstdint>
#include <vector>

#include "reference/lightassign/light_bvh.h"
#include "shadowcts/case.h"

namespace shadowcts::simd {

// Boxes as structure of arrays; entries past `count` up to a multiple of 32 are empty
// (min = +inf, max = -inf), so a 32-wide load never reads past the end and never overlaps.
struct BoxArrays {
  std::vector<float> min[3], max[3];
  std::size_t count = 0;
};

struct LightBvhLanes {
  static constexpr std::uint32_t branching = LightBvh::branching;

  // Refers to `bvh` and `lights`: they must outlive it.
  LightBvhLanes(const LightBvh& bvh, const std::vector<RangedLight>& lights);

  std::vector<BoxArrays> levels;  // as LightBvh::levels(): [0] over the leaves, last: the root
  // The leaves are read where the reference keeps them (a leaf node's 32 boxes are gathered from
  // its box array, 6 floats per leaf: min xyz, max xyz), not copied: at a million lights the copy
  // would cost as much as the traversal.
  const float* leaf_boxes = nullptr;
  std::size_t leaf_count = 0;
  const std::uint32_t* order = nullptr;  // LightBvh::light_order
  const RangedLight* lights = nullptr;
};

}  // namespace shadowcts::simd
