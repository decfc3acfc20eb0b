// Per-target inline code shared by the simd ports' Highway translation units: a mask's lanes as
// the bits of an integer, which the ports' loops walk (lowest set bit first) and combine.
#if defined(SHADOWCTS_SIMD_LANE_BITS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SHADOWCTS_SIMD_LANE_BITS_INL_H_
#undef SHADOWCTS_SIMD_LANE_BITS_INL_H_
#else
#define SHADOWCTS_SIMD_LANE_BITS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>
#include <cstring>

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Bit i set for lane i of `mask` (at most 64 lanes); no bit past the vector's lanes.
template <class D, class M>
HWY_INLINE std::uint64_t lane_bits(D d, M mask) {
  static_assert(hn::MaxLanes(D()) <= 64);
#if HWY_TARGET <= HWY_AVX3
  // An AVX-512 mask register holds the lane bits: no round trip through memory (the ports'
  // loops read several masks per step). A vector narrower than its register may leave bits above
  // its lanes.
  (void)d;
  std::uint64_t bits = std::uint64_t(mask.raw);
  if constexpr (hn::MaxLanes(D()) < 64) bits &= (std::uint64_t(1) << hn::MaxLanes(D())) - 1;
  return bits;
#else
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  return bits;
#endif
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd
HWY_AFTER_NAMESPACE();

#endif  // SHADOWCTS_SIMD_LANE_BITS_INL_H_
