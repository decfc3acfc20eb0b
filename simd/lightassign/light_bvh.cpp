#include "simd/lightassign/light_bvh.h"

#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowcts::simd {
namespace {

std::size_t padded(std::size_t count) {
  return (count + LightBvh::branching - 1) / LightBvh::branching * LightBvh::branching;
}

BoxArrays box_arrays(std::size_t count, auto&& box_of) {
  BoxArrays out;
  out.count = count;
  const std::size_t size = padded(count);
  for (int k = 0; k < 3; ++k) {
    out.min[k].assign(size, std::numeric_limits<float>::infinity());
    out.max[k].assign(size, -std::numeric_limits<float>::infinity());
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Aabb& box = box_of(i);
      for (int k = 0; k < 3; ++k) {
        out.min[k][i] = box.min[k];
        out.max[k][i] = box.max[k];
      }
    }
  });
  return out;
}

}  // namespace

LightBvhLanes::LightBvhLanes(const LightBvh& bvh, const std::vector<RangedLight>& light_list) {
  static_assert(sizeof(Aabb) == 6 * sizeof(float), "Aabb: min xyz, max xyz, no padding");
  for (const std::vector<Aabb>& level : bvh.levels())
    levels.push_back(
        box_arrays(level.size(), [&](std::size_t i) -> const Aabb& { return level[i]; }));
  leaf_count = bvh.light_order().size();
  if (leaf_count > 0) leaf_boxes = &bvh.leaf_box(0).min.x;
  order = bvh.light_order().data();
  lights = light_list.data();
}

}  // namespace shadowcts::simd
