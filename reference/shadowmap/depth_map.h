#pragma once
// One square light-space depth map: the closest caster depth seen through each texel.
#include <cstdint>
#include <limits>
#include <vector>

namespace shadowcts::shadowmap {

struct DepthMap {
  std::uint32_t resolution = 0;
  // Row-major, resolution x resolution; +infinity where no caster was rasterized.
  std::vector<float> depth;

  void reset(std::uint32_t n) {
    resolution = n;
    depth.assign(std::size_t(n) * n, std::numeric_limits<float>::infinity());
  }
  float at(std::uint32_t column, std::uint32_t row) const {
    return depth[std::size_t(row) * resolution + column];
  }
};

}  // namespace shadowcts::shadowmap
