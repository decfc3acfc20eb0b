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

LightBvhLanes::LightBvhLanes(const LightBvh& bvh, const std::vector<RangedLight>& lights) {
  for (const std::vector<Aabb>& level : bvh.levels())
    levels.push_back(
        box_arrays(level.size(), [&](std::size_t i) -> const Aabb& { return level[i]; }));
  const std::size_t n = bvh.light_order().size();
  leaves =
      box_arrays(n, [&](std::size_t i) -> const Aabb& { return bvh.leaf_box(std::uint32_t(i)); });
  order = bvh.light_order();
  const std::size_t size = padded(n);
  for (int k = 0; k < 3; ++k) {
    centre[k].assign(size, 0.0f);
    centre_d[k].assign(size, 0.0);
  }
  range.assign(size, 0.0f);
  range_squared.assign(size, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t leaf = r.begin(); leaf != r.end(); ++leaf) {
      const RangedLight& l = lights[order[leaf]];
      for (int k = 0; k < 3; ++k) {
        centre[k][leaf] = l.centre[k];
        centre_d[k][leaf] = double(l.centre[k]);
      }
      range[leaf] = l.range;
      range_squared[leaf] = double(l.range) * double(l.range);  // exact: 48 bits
    }
  });
}

}  // namespace shadowcts::simd
