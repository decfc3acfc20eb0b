#pragma once
// The per-fragment disk bitmask on the device: reference/softtile/disk_bitmask.cpp's
// clear_triangle on a thread's own rows (one 32-bit word per scanline, column 0 the most
// significant used bit), each edge's scanline crossing with the reference's float operations in
// its order, rounded once, so the masks are the reference's bit for bit.
#include <bit>
#include <cmath>
#include <cstdint>

#include "gpu/emulator/kernel.h"
#include "gpu/softtile/softtile_kernel.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace softtile {

__device__ inline float round_up(float x) {
#if SHADOWCTS_EMULATED
  return std::ceil(x);
#else
  return ceilf(x);
#endif
}

__device__ inline int bit_count(std::uint32_t x) {
#if SHADOWCTS_EMULATED
  return std::popcount(x);
#else
  return __popc(x);
#endif
}

// Clears the cells inside the triangle (edge functions edges[0..8]) from rows[0..raster.rows).
__device__ inline void clear_triangle(const SofttileRaster& raster, const float edges[9],
                                      std::uint32_t rows[softtile_kernel_max_rows]) {
  const float columns = float(raster.columns);
  for (int r = 0; r < raster.rows; ++r) {
    if (rows[r] == 0) continue;  // stays 0 under the AND
    const float y = raster.y[r];
    std::uint32_t outside = 0;
    for (int k = 0; k < 3; ++k) {
      const float ex = edges[3 * k], ey = edges[3 * k + 1], ez = edges[3 * k + 2];
      const float offset = rounded_add(rounded_mul(ey, y), ez);
      if (ex == 0.0f) {
        if (offset < 0.0f) outside = raster.full_row;
        continue;
      }
      // The count n of cell centres left of the edge's crossing with this scanline.
      const float crossing = rounded_div(-offset, ex);
      const float u =
          rounded_sub(rounded_mul(rounded_add(crossing, 1.0f), raster.half_columns), 0.5f);
      const int n = !(u > 0.0f) ? 0 : (u >= columns ? raster.columns : int(round_up(u)));
      const std::uint32_t right_of_edge = raster.full_row >> n;
      // 1s mark the outside of the edge: left of it when the inside is to the right.
      outside |= ex > 0.0f ? (raster.full_row & ~right_of_edge) : right_of_edge;
    }
    rows[r] &= outside;
  }
}

}  // namespace softtile
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
