#pragma once
// The reference's light BVH (reference/lightassign/light_bvh.h: its definition, built by it) laid
// out for Highway loads: every level's boxes as structure of arrays, padded to whole nodes of 32
// with boxes that overlap nothing, and the leaves' spheres in Morton order as doubles for the
// sphere/box filter.
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

  LightBvhLanes(const LightBvh& bvh, const std::vector<RangedLight>& lights);

  std::vector<BoxArrays> levels;     // as LightBvh::levels(): [0] over the leaves, last: the root
  BoxArrays leaves;                  // LightBvh::leaf_box per leaf
  std::vector<std::uint32_t> order;  // LightBvh::light_order
  // Per leaf (padded like the boxes): the light's centre and range as floats (for the exact
  // test) and as doubles, with the exact range squared (for the filter).
  std::vector<float> centre[3], range;
  std::vector<double> centre_d[3], range_squared;
};

}  // namespace shadowcts::simd
