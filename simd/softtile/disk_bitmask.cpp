// Highway translation unit of the simd softtile's disk bitmask (see disk_bitmask.h); the
// rasterization itself is disk_bitmask-inl.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/disk_bitmask.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

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

// The set bits of the padded rows, in lanes (the baseline build has no popcount instruction:
// std::popcount there is a libgcc call per row, 1.8 % of the run at foliage.100k).
int LitCells(const std::uint32_t* bits) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::ScalableTag<std::uint32_t> d;
  auto sum = hn::Zero(d);
  for (std::size_t r = 0; r < std::size_t(padded_rows); r += hn::Lanes(d))
    sum = hn::Add(sum, hn::PopulationCount(hn::Load(d, bits + r)));
  return int(hn::GetLane(hn::SumOfLanes(d, sum)));
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd::softtile
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::softtile {

HWY_EXPORT(ClearTriangles);
HWY_EXPORT(LitCells);

int DiskRows::lit_cells() const {
  return HWY_DYNAMIC_DISPATCH(LitCells)(bits.data());
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
