// The one Highway translation unit of the simd softtile (see disk_bitmask.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/disk_bitmask.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <bit>

#include "reference/softtile/disk_bitmask.h"
#include "simd/softtile/disk_bitmask.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// DiskBitmask::clear_triangle for every triangle, scanlines in lanes. The mask's rows stay in
// registers across the triangles; a row that is already 0 stays 0 under the AND, which is all the
// reference's skip of empty rows does.
void ClearTriangles(const DiskRaster::Setup& s, const glm::vec3* edges, std::size_t count,
                    std::uint32_t* bits) {
  const hn::ScalableTag<float> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::RebindToSigned<decltype(df)> di;
  const std::size_t lanes = hn::Lanes(df);
  const auto full = hn::Set(du, s.full_row);
  const auto zero = hn::Zero(df);
  const auto one = hn::Set(df, 1.0f);
  const auto half = hn::Set(df, 0.5f);
  const auto half_columns = hn::Set(df, s.half_columns);
  const auto columns = hn::Set(df, float(s.columns));
  for (std::size_t r0 = 0; r0 < std::size_t(s.rows); r0 += lanes) {
    const auto y = hn::Load(df, s.y + r0);
    auto row = hn::Load(du, bits + r0);
    for (std::size_t t = 0; t < count; ++t) {
      auto outside = hn::Zero(du);
      for (int k = 0; k < 3; ++k) {
        const glm::vec3& e = edges[3 * t + k];
        // e.y * y + e.z: a product, then a sum (no fused multiply-add, as the reference).
        const auto offset = hn::Add(hn::Mul(hn::Set(df, e.y), y), hn::Set(df, e.z));
        if (e.x == 0.0f) {
          outside =
              hn::Or(outside, hn::IfThenElseZero(hn::RebindMask(du, hn::Lt(offset, zero)), full));
          continue;
        }
        const auto crossing = hn::Div(hn::Neg(offset), hn::Set(df, e.x));
        const auto u = hn::Sub(hn::Mul(hn::Add(crossing, one), half_columns), half);
        // n = !(u > 0) ? 0 : (u >= columns ? columns : ceil(u)); NaN gives 0 as in the reference.
        const auto n = hn::IfThenElse(
            hn::Gt(u, zero), hn::IfThenElse(hn::Ge(u, columns), columns, hn::Ceil(u)), zero);
        const auto right_of_edge = hn::BitCast(du, hn::ConvertTo(di, n));
        const auto right = hn::operator>>(full, right_of_edge);
        outside = hn::Or(outside, e.x > 0.0f ? hn::AndNot(right, full) : right);
      }
      row = hn::And(row, outside);
    }
    hn::Store(row, du, bits + r0);
  }
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
