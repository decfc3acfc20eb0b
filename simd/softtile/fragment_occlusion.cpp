// Highway translation unit of the simd softtile's fragment setup (see fragment_occlusion.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/fragment_occlusion.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <limits>

#include "simd/softtile/fragment_occlusion.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<float>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

struct V3 {
  V x, y, z;
};

// glm::cross(a, b) = (a.y b.z - b.y a.z, a.z b.x - b.z a.x, a.x b.y - b.x a.y).
HWY_INLINE V3 cross(const V3& a, const V3& b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(b.y, a.z)),
          hn::Sub(hn::Mul(a.z, b.x), hn::Mul(b.z, a.x)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(b.x, a.y))};
}

// glm::dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
HWY_INLINE V dot(const V3& a, const V3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}

std::size_t TriangleEdges(const FragmentArrays& f, const std::array<glm::vec3, 3>& light_space,
                          std::uint32_t triangle, std::uint64_t* accepted, float* edges,
                          std::size_t stride) {
  const D d;
  const hn::RebindToUnsigned<D> du;
  const std::size_t lanes = hn::Lanes(d);
  const V zero = hn::Zero(d);
  const V inverse_scale = hn::Set(d, f.inverse_scale);
  const auto receiver_id = hn::Set(du, triangle);
  // Lanes fill whole bytes of the bit rows (at least 8 float lanes on every target but SCALAR,
  // whose single lane writes one bit of a byte at a time).
  auto* bytes = reinterpret_cast<std::uint8_t*>(accepted);
  std::fill(bytes, bytes + 8 * f.words(), std::uint8_t(0));
  std::size_t tests = 0;
  for (std::size_t j = 0; j < f.size; j += lanes) {
    const M tested =
        hn::And(hn::FirstN(d, f.size - j),
                hn::RebindMask(d, hn::Ne(hn::LoadU(du, f.receiver.data() + j), receiver_id)));
    tests += hn::CountTrue(d, tested);
    const V px = hn::LoadU(d, f.x.data() + j), py = hn::LoadU(d, f.y.data() + j),
            pz = hn::LoadU(d, f.z.data() + j);
    const V c = hn::LoadU(d, f.cos_rotation.data() + j),
            s = hn::LoadU(d, f.sin_rotation.data() + j);
    V3 h[3];
    M any_front = hn::Lt(zero, zero);  // all false
    for (int i = 0; i < 3; ++i) {
      const V tx = hn::Sub(hn::Set(d, light_space[i].x), px);
      const V ty = hn::Sub(hn::Set(d, light_space[i].y), py);
      const V tz = hn::Sub(hn::Set(d, light_space[i].z), pz);
      const V x = hn::Mul(tx, inverse_scale), y = hn::Mul(ty, inverse_scale);
      // Rotating the triangle by the angle rotates the grid by its opposite: the disk is round.
      h[i] = {hn::Sub(hn::Mul(c, x), hn::Mul(s, y)), hn::Add(hn::Mul(s, x), hn::Mul(c, y)), tz};
      any_front = hn::Or(any_front, hn::Gt(tz, zero));
    }
    const V det = dot(h[0], cross(h[1], h[2]));
    // det != 0 and finite: |det| < inf is false for NaN and for infinities.
    M ok =
        hn::And(hn::And(tested, any_front),
                hn::And(hn::Ne(det, zero),
                        hn::Lt(hn::Abs(det), hn::Set(d, std::numeric_limits<float>::infinity()))));
    if (hn::AllFalse(d, ok)) continue;
    const V sign = hn::IfThenElse(hn::Gt(det, zero), hn::Set(d, 1.0f), hn::Set(d, -1.0f));
    V3 e[3];
    for (int i = 0; i < 3; ++i) {
      const V3 edge = cross(h[i], h[(i + 1) % 3]);
      e[i] = {hn::Mul(sign, edge.x), hn::Mul(sign, edge.y), hn::Mul(sign, edge.z)};
      // The disk lies entirely outside this edge.
      const M outside = hn::And(hn::Lt(e[i].z, zero),
                                hn::Gt(hn::Mul(e[i].z, e[i].z),
                                       hn::Add(hn::Mul(e[i].x, e[i].x), hn::Mul(e[i].y, e[i].y))));
      ok = hn::AndNot(outside, ok);
    }
    if (hn::AllFalse(d, ok)) continue;
    for (int i = 0; i < 3; ++i) {
      hn::StoreU(e[i].x, d, edges + (3 * i + 0) * stride + j);
      hn::StoreU(e[i].y, d, edges + (3 * i + 1) * stride + j);
      hn::StoreU(e[i].z, d, edges + (3 * i + 2) * stride + j);
    }
    if (lanes >= 8) {
      hn::StoreMaskBits(d, ok, bytes + j / 8);
    } else {
      std::uint8_t bits = 0;
      hn::StoreMaskBits(d, ok, &bits);
      bytes[j / 8] |= std::uint8_t(bits << (j % 8));
    }
  }
  return tests;
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd::softtile
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::softtile {

HWY_EXPORT(TriangleEdges);

void FragmentArrays::assign(const std::vector<shadowcts::softtile::FragmentSetup>& fragments,
                            const std::vector<std::uint32_t>& receivers) {
  size = fragments.size();
  const std::size_t padded = (size + fragment_padding - 1) / fragment_padding * fragment_padding;
  for (std::vector<float>* v : {&x, &y, &z, &cos_rotation, &sin_rotation}) v->assign(padded, 0.0f);
  receiver.assign(padded, 0u);
  for (std::size_t j = 0; j < size; ++j) {
    receiver[j] = receivers[j];
    x[j] = fragments[j].position.x;
    y[j] = fragments[j].position.y;
    z[j] = fragments[j].position.z;
    cos_rotation[j] = fragments[j].cos_rotation;
    sin_rotation[j] = fragments[j].sin_rotation;
  }
  if (size != 0) inverse_scale = fragments[0].inverse_scale;
}

std::size_t triangle_edges(const FragmentArrays& fragments,
                           const std::array<glm::vec3, 3>& light_space, std::uint32_t triangle,
                           std::uint64_t* accepted, float* edges, std::size_t stride) {
  return HWY_DYNAMIC_DISPATCH(TriangleEdges)(fragments, light_space, triangle, accepted, edges,
                                             stride);
}

}  // namespace shadowcts::simd::softtile
#endif  // HWY_ONCE
