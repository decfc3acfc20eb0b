// Highway translation unit of the simd softtile's disk bitmask (see disk_bitmask.h); the
// rasterization itself is disk_bitmask-inl.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/disk_bitmask.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <bit>

#include "reference/softtile/disk_bitmask.h"
#include "simd/softtile/disk_bitmask-inl.h"
#include "simd/softtile/disk_bitmask.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {

void ClearTriangles(const DiskRaster::Setup& s, const glm::vec3* edges, std::size_t count,
                    std::uint32_t* bits) {
  ClearTriangleRows(s, edges, count, bits);
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd::softtile
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::softtile {

HWY_EXPORT(ClearTriangles);

int DiskRows::lit_cells() const {
  int count = 0;
  for (std::uint32_t row : bits) count += std::popcount(row);
  return count;
}

DiskRaster::DiskRaster(const shadowcts::softtile::Variant& variant)
    : rows_(variant.rows), columns_(variant.columns) {
  const shadowcts::softtile::DiskBitmask disk(variant);
  disk_cells_ = disk.disk_cells();
  setup_.rows = rows_;
  setup_.columns = columns_;
  setup_.full_row = columns_ == 32 ? 0xffffffffu : (1u << columns_) - 1u;
  setup_.half_columns = 0.5f * float(columns_);
  for (int r = 0; r < padded_rows; ++r) {
    setup_.y[r] = r < rows_ ? -1.0f + (float(r) + 0.5f) * 2.0f / float(rows_) : 0.0f;
    empty_.bits[r] = r < rows_ ? disk.row(r) : 0u;
  }
}

void DiskRaster::clear_triangles(const glm::vec3* edges, std::size_t count, DiskRows& mask) const {
  if (count == 0) return;
  HWY_DYNAMIC_DISPATCH(ClearTriangles)(setup_, edges, count, mask.bits.data());
}

}  // namespace shadowcts::simd::softtile
#endif  // HWY_ONCE
