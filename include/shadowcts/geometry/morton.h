#pragma once
// Morton order, for host and device: the bit spreading behind the 63-bit codes that order lights
// (lightassign's BVH), triangles (metric's clustering) and shadow cones (the simd softtile's cone
// tree). Integer operations only, so every backend computes the same codes.
#include <algorithm>
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/host_device.h"

// The namespaces opened as in normal_cone.h, which the device kernels include beside this.
namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN
namespace geometry {

// The low 21 bits of x, each followed by two zero bits.
SHADOWCTS_HD inline std::uint64_t spread_bits_21(std::uint64_t x) {
  x &= 0x1fffffull;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// The Morton code of `point` in the box from `lo` spanning `extent`: per axis the position in
// [0, 1] (0 where the extent is 0), clamped, times 2^21 - 1, truncated; x in the lowest bit.
inline std::uint64_t morton_code_in_box(const glm::dvec3& point, const glm::dvec3& lo,
                                        const glm::dvec3& extent) {
  std::uint64_t code = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const double unit = extent[axis] > 0.0 ? (point[axis] - lo[axis]) / extent[axis] : 0.0;
    const auto cell = std::uint64_t(std::clamp(unit, 0.0, 1.0) * double((1u << 21) - 1));
    code |= spread_bits_21(cell) << axis;
  }
  return code;
}

}  // namespace geometry
SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
