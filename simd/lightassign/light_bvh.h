#pragma once
// The reference's light BVH (reference/lightassign/light_bvh.h: Morton order of the centres over
// their box, 32 leaves per node, 32 nodes per node above) built in parallel and in Highway lanes,
// laid out for Highway loads: the Morton codes in lanes, a parallel radix sort of the keys, the
// leaves' spheres in Morton order and every level's node boxes in lanes as structure of arrays.
// The leaf boxes are not stored: the queries and the first level derive what they need of them
// from the spheres (lightassign_kernels.cpp). The same order and node boxes as LightBvh, bit for
// bit, and the same leaf box decisions (tests/simd/lightassign/ diff them on every Highway
// target).
#include <cstdint>
#include <vector>

#include "reference/lightassign/light_bvh.h"
#include "shadowcts/case.h"
#include "simd/lightassign/uninitialized_vector.h"

namespace shadowcts::simd {

// Boxes as structure of arrays; entries past `count` up to a multiple of 32 are empty
// (min = +inf, max = -inf), so a 32-wide load never reads past the end and never overlaps.
struct BoxArrays {
  UninitializedVector<float> min[3], max[3];
  std::size_t count = 0;

  // Sized for `count` boxes, the padding set to empty boxes, the rest unset.
  void resize(std::size_t count);
};

struct LightBvhLanes {
  static constexpr std::uint32_t branching = LightBvh::branching;

  explicit LightBvhLanes(const std::vector<RangedLight>& lights);

  UninitializedVector<std::uint32_t> order;  // LightBvh::light_order: the light index of each leaf
  // Each leaf's sphere (centre x, y, z and range, the light's floats), padded to a multiple of 32
  // with NaN centres (which overlap nothing): the leaf test loads them instead of gathering the
  // lights.
  UninitializedVector<float> sphere[4];
  std::vector<BoxArrays> levels;  // as LightBvh::levels(): [0] over the leaves, last: the root
};

}  // namespace shadowcts::simd
