#include "reference/softtile/disk_bitmask.h"

#include <bit>
#include <cmath>

namespace shadowcts::softtile {
namespace {

// The post's 16 x 16 disk, two 16-bit rows per word, the upper half first.
constexpr std::array<std::uint32_t, 8> post_grid16_disk{
    0x07e01ff8u, 0x3ffc7ffeu, 0x7ffeffffu, 0xffffffffu,
    0xffffffffu, 0xffff7ffeu, 0x7ffe3ffcu, 0x1ff807e0u,
};

}  // namespace

DiskBitmask::DiskBitmask(const Variant& variant)
    : rows_(variant.rows),
      columns_(variant.columns),
      full_row_(variant.columns == 32 ? 0xffffffffu : (1u << variant.columns) - 1u) {
  if (columns_ == 16 && rows_ == 16) {
    for (int r = 0; r < 16; ++r)
      bits_[r] = r % 2 == 0 ? post_grid16_disk[r / 2] >> 16 : post_grid16_disk[r / 2] & 0xffffu;
  } else {
    for (int r = 0; r < rows_; ++r) {
      const double y = -1.0 + (r + 0.5) * 2.0 / rows_;
      for (int c = 0; c < columns_; ++c) {
        const double x = -1.0 + (c + 0.5) * 2.0 / columns_;
        if (x * x + y * y <= 1.0) bits_[r] |= 1u << (columns_ - 1 - c);
      }
    }
  }
  disk_cells_ = lit_cells();
}

int DiskBitmask::lit_cells() const {
  int count = 0;
  for (int r = 0; r < rows_; ++r) count += std::popcount(bits_[r]);
  return count;
}

void DiskBitmask::clear_triangle(const std::array<glm::vec3, 3>& edges) {
  const float half_columns = 0.5f * float(columns_);
  for (int r = 0; r < rows_; ++r) {
    if (bits_[r] == 0) continue;
    const float y = -1.0f + (float(r) + 0.5f) * 2.0f / float(rows_);
    std::uint32_t outside = 0;
    for (const glm::vec3& e : edges) {
      const float offset = e.y * y + e.z;
      if (e.x == 0.0f) {
        if (offset < 0.0f) outside = full_row_;
        continue;
      }
      // Crossing X* of the edge with this scanline, as the count n of cell centres left of it:
      // X_c < X*  <=>  c < (X* + 1) columns / 2 - 0.5.
      const float crossing = -offset / e.x;
      const float u = (crossing + 1.0f) * half_columns - 0.5f;
      const int n = !(u > 0.0f) ? 0 : (u >= float(columns_) ? columns_ : int(std::ceil(u)));
      const std::uint32_t right_of_edge = full_row_ >> n;  // 1s right of the edge
      // Flip so that 1s mark the outside of the edge: left of it when the inside is to the right.
      outside |= e.x > 0.0f ? (full_row_ & ~right_of_edge) : right_of_edge;
    }
    bits_[r] &= outside;
  }
}

}  // namespace shadowcts::softtile
