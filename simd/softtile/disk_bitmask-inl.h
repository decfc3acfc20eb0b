// Per-target inline code of the simd softtile's disk bitmask rasterization (disk_bitmask.h), for
// the Highway translation units that rasterize: disk_bitmask.cpp and fragment_occlusion.cpp.
#if defined(SHADOWCTS_SIMD_SOFTTILE_DISK_BITMASK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SHADOWCTS_SIMD_SOFTTILE_DISK_BITMASK_INL_H_
#undef SHADOWCTS_SIMD_SOFTTILE_DISK_BITMASK_INL_H_
#else
#define SHADOWCTS_SIMD_SOFTTILE_DISK_BITMASK_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "simd/softtile/disk_bitmask.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// DiskBitmask::clear_triangle for every triangle, scanlines in lanes. The mask's rows stay in
// registers across the triangles; a row that is already 0 stays 0 under the AND, which is all the
// reference's skip of empty rows does.
HWY_INLINE void ClearTriangleRows(const DiskRaster::Setup& s, const glm::vec3* edges,
                                  std::size_t count, std::uint32_t* bits) {
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

#endif  // SHADOWCTS_SIMD_SOFTTILE_DISK_BITMASK_INL_H_
