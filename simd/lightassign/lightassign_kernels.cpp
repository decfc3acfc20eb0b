// The one Highway translation unit of the simd `lightassign` (see lightassign_kernels.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/lightassign/lightassign_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
// The logarithm of the slice keys.
#include <hwy/contrib/math/math-inl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/geometry/sphere_box.h"
#include "simd/lane_bits-inl.h"
#include "simd/lightassign/lightassign_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

constexpr std::size_t node_width = LightBvh::branching;  // 32

// LightBvh::overlap(boxes[first + i], box) for the 32 boxes from `first`, as bits.
HWY_INLINE std::uint32_t overlap_bits(const BoxArrays& boxes, std::size_t first, const Aabb& box) {
  const hn::CappedTag<float, node_width> d;
  const std::size_t lanes = hn::Lanes(d);
  const auto qmin_x = hn::Set(d, box.min.x), qmin_y = hn::Set(d, box.min.y),
             qmin_z = hn::Set(d, box.min.z);
  const auto qmax_x = hn::Set(d, box.max.x), qmax_y = hn::Set(d, box.max.y),
             qmax_z = hn::Set(d, box.max.z);
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < node_width; i += lanes) {
    const std::size_t at = first + i;
    auto m = hn::And(hn::Le(hn::LoadU(d, boxes.min[0].data() + at), qmax_x),
                     hn::Le(qmin_x, hn::LoadU(d, boxes.max[0].data() + at)));
    m = hn::And(m, hn::And(hn::Le(hn::LoadU(d, boxes.min[1].data() + at), qmax_y),
                           hn::Le(qmin_y, hn::LoadU(d, boxes.max[1].data() + at))));
    m = hn::And(m, hn::And(hn::Le(hn::LoadU(d, boxes.min[2].data() + at), qmax_z),
                           hn::Le(qmin_z, hn::LoadU(d, boxes.max[2].data() + at))));
    bits |= lane_bits(d, m) << i;
  }
  return std::uint32_t(bits);
}

// The reference's double filter of sphere_meets_box on lanes: `inside` where the squared
// distance plus its error bound is below r^2, `outside` where minus the bound it is above.
template <class D, class V>
HWY_INLINE void sphere_box_filter(D d, const V cx, const V cy, const V cz, const V r2,
                                  const Aabb& box, std::uint64_t& inside, std::uint64_t& outside) {
  const V zero = hn::Zero(d);
  V distance2 = zero, magnitude2 = zero;
  const V c[3] = {cx, cy, cz};
  for (int k = 0; k < 3; ++k) {
    const V low = hn::Set(d, double(box.min[k])), high = hn::Set(d, double(box.max[k]));
    // Rounding is monotone: the max of the rounded gaps is the rounded true gap.
    const V gap = hn::Max(zero, hn::Max(hn::Sub(low, c[k]), hn::Sub(c[k], high)));
    const V b = hn::Add(hn::Add(hn::Abs(low), hn::Abs(c[k])), hn::Abs(high));
    distance2 = hn::Add(distance2, hn::Mul(gap, gap));
    magnitude2 = hn::Add(magnitude2, hn::Mul(b, b));
  }
  const V error = hn::Add(hn::Mul(hn::Set(d, geometry::sphere_box_error_scale), magnitude2),
                          hn::Set(d, geometry::sphere_box_underflow_guard));
  inside = lane_bits(d, hn::Lt(hn::Add(distance2, error), r2));
  outside = lane_bits(d, hn::Gt(hn::Sub(distance2, error), r2));
}

// LightBvh::overlap(leaf box, box) from the leaf's sphere, without its box: the leaf box is
// [round_down(c - r), round_up(c + r)] (c - r and c + r in double), round_down(x) the largest float
// <= x and round_up(x) the smallest float >= x, so round_down(x) <= M for a float M exactly when
// x < the float after M, and round_up(x) >= m exactly when x > the float before m.
struct LeafTest {
  double below_min[3], above_max[3];
  float below_min_float[3], above_max_float[3];
  explicit LeafTest(const Aabb& box) {
    for (int k = 0; k < 3; ++k) {
      below_min_float[k] = std::nextafter(box.min[k], -std::numeric_limits<float>::infinity());
      above_max_float[k] = std::nextafter(box.max[k], std::numeric_limits<float>::infinity());
      below_min[k] = double(below_min_float[k]);
      above_max[k] = double(above_max_float[k]);
    }
  }
  // A necessary condition for `overlaps` in float lanes (twice as many): rounding is monotone,
  // so c - r < M (a float) in double makes c - r <= M in float, and c + r > m makes c + r >= m.
  template <class D, class V>
  HWY_INLINE auto may_overlap(D d, V cx, V cy, V cz, V r) const {
    const V c[3] = {cx, cy, cz};
    auto m = hn::And(hn::Le(hn::Sub(c[0], r), hn::Set(d, above_max_float[0])),
                     hn::Ge(hn::Add(c[0], r), hn::Set(d, below_min_float[0])));
    for (int k = 1; k < 3; ++k)
      m = hn::And(m, hn::And(hn::Le(hn::Sub(c[k], r), hn::Set(d, above_max_float[k])),
                             hn::Ge(hn::Add(c[k], r), hn::Set(d, below_min_float[k]))));
    return m;
  }
  template <class D, class V>
  HWY_INLINE auto overlaps(D d, V cx, V cy, V cz, V r) const {
    const V c[3] = {cx, cy, cz};
    auto m = hn::And(hn::Lt(hn::Sub(c[0], r), hn::Set(d, above_max[0])),
                     hn::Gt(hn::Add(c[0], r), hn::Set(d, below_min[0])));
    for (int k = 1; k < 3; ++k)
      m = hn::And(m, hn::And(hn::Lt(hn::Sub(c[k], r), hn::Set(d, above_max[k])),
                             hn::Gt(hn::Add(c[k], r), hn::Set(d, below_min[k]))));
    return m;
  }
};

// The 32 leaves from `first` against `box`: per lane the leaf box test (on the sphere, see
// LeafTest) and the exact filter's sure answers, then in leaf order the exact test where the filter
// is unsure; the lights that meet the box are appended. The padding's NaN centres fail the box
// test.
HWY_INLINE void test_leaves(const LightBvhLanes& bvh, const LeafTest& leaf, const Aabb& box,
                            std::size_t first, std::vector<std::uint32_t>& list, ListWork& w) {
  const hn::ScalableTag<double> dd;
  const hn::Rebind<float, decltype(dd)> df;
  const std::size_t dlanes = hn::Lanes(dd);
  const std::uint64_t dlane_mask = dlanes >= 64 ? ~0ull : (1ull << dlanes) - 1;
  w.nodes_tested += std::min(first + node_width, bvh.order.size()) - first;
  // The float lanes' necessary condition first: the double lanes test only the leaves it keeps.
  const hn::CappedTag<float, node_width> dwide;
  const std::size_t wide_lanes = hn::Lanes(dwide);
  std::uint64_t candidates = 0;
  for (std::size_t i = 0; i < node_width; i += wide_lanes) {
    const std::size_t at = first + i;
    const auto maybe = leaf.may_overlap(dwide, hn::LoadU(dwide, bvh.sphere[0].data() + at),
                                        hn::LoadU(dwide, bvh.sphere[1].data() + at),
                                        hn::LoadU(dwide, bvh.sphere[2].data() + at),
                                        hn::LoadU(dwide, bvh.sphere[3].data() + at));
    candidates |= lane_bits(dwide, maybe) << i;
  }
  if (candidates == 0) return;
  std::uint64_t overlapping = 0, inside = 0, outside = 0;
  for (std::size_t i = 0; i < node_width; i += dlanes) {
    if (((candidates >> i) & dlane_mask) == 0) continue;
    const std::size_t at = first + i;
    const auto r = hn::PromoteTo(dd, hn::LoadU(df, bvh.sphere[3].data() + at));
    const auto cx = hn::PromoteTo(dd, hn::LoadU(df, bvh.sphere[0].data() + at));
    const auto cy = hn::PromoteTo(dd, hn::LoadU(df, bvh.sphere[1].data() + at));
    const auto cz = hn::PromoteTo(dd, hn::LoadU(df, bvh.sphere[2].data() + at));
    const std::uint64_t hit = lane_bits(dd, leaf.overlaps(dd, cx, cy, cz, r));
    if (hit == 0) continue;
    overlapping |= hit << i;
    std::uint64_t in_bits = 0, out_bits = 0;
    sphere_box_filter(dd, cx, cy, cz, hn::Mul(r, r), box, in_bits, out_bits);  // r^2: exact
    inside |= (in_bits & dlane_mask) << i;
    outside |= (out_bits & dlane_mask) << i;
  }
  if (overlapping == 0) return;
  w.light_tests += std::uint64_t(std::popcount(overlapping));
  for (std::uint64_t bits = overlapping; bits != 0; bits &= bits - 1) {
    const std::size_t i = std::size_t(std::countr_zero(bits)), leaf_index = first + i;
    bool meets = (inside >> i) & 1u;
    if (!meets && !((outside >> i) & 1u))
      meets = geometry::sphere_meets_box_exact(
          glm::vec3(bvh.sphere[0][leaf_index], bvh.sphere[1][leaf_index],
                    bvh.sphere[2][leaf_index]),
          bvh.sphere[3][leaf_index], box.min, box.max);
    if (meets) list.push_back(bvh.order[leaf_index]);
  }
}

// The brute force: every leaf, no node tested.
ListWork TestEveryLight(const LightBvhLanes& bvh, const Aabb& box,
                        std::vector<std::uint32_t>& list) {
  ListWork w;
  const LeafTest leaf(box);
  for (std::size_t first = 0; first < bvh.order.size(); first += node_width)
    test_leaves(bvh, leaf, box, first, list, w);
  return w;
}

ListWork QueryLightBvh(const LightBvhLanes& bvh, const Aabb& box,
                       std::vector<std::uint32_t>& list) {
  ListWork w;
  if (bvh.levels.empty()) return w;
  w.nodes_tested = 1;
  const std::size_t top = bvh.levels.size() - 1;
  if (!(overlap_bits(bvh.levels[top], 0, box) & 1u)) return w;
  struct Entry {
    std::uint32_t level, node;
  };
  Entry stack[64 * node_width];
  std::size_t size = 0;
  stack[size++] = {std::uint32_t(top), 0};
  const LeafTest leaf(box);
  while (size > 0) {
    const Entry e = stack[--size];
    const std::size_t first = std::size_t(e.node) * node_width;
    if (e.level == 0) {
      test_leaves(bvh, leaf, box, first, list, w);
      continue;
    }
    const BoxArrays& children = bvh.levels[e.level - 1];
    const std::size_t last = std::min(first + node_width, children.count);
    w.nodes_tested += last - first;
    // Pushed from the last child down, so they pop in order (as the reference).
    for (std::uint32_t bits = overlap_bits(children, first, box); bits != 0;) {
      const int i = 31 - std::countl_zero(bits);
      bits &= ~(1u << i);
      stack[size++] = {e.level - 1, std::uint32_t(first + std::size_t(i))};
    }
  }
  return w;
}

// LightBvh's Morton code: per axis t = (centre - low) / extent, q = the integer part of
// clamp(t 2^21, 0, 2^21 - 1), its 21 bits spread to every third bit (x highest).
template <class D, class V>
HWY_INLINE V spread_every_third(D du, V x) {
  x = hn::And(hn::Or(x, hn::ShiftLeft<32>(x)), hn::Set(du, 0x1f00000000ffffull));
  x = hn::And(hn::Or(x, hn::ShiftLeft<16>(x)), hn::Set(du, 0x1f0000ff0000ffull));
  x = hn::And(hn::Or(x, hn::ShiftLeft<8>(x)), hn::Set(du, 0x100f00f00f00f00full));
  x = hn::And(hn::Or(x, hn::ShiftLeft<4>(x)), hn::Set(du, 0x10c30c30c30c30c3ull));
  return hn::And(hn::Or(x, hn::ShiftLeft<2>(x)), hn::Set(du, 0x1249249249249249ull));
}

void MortonCodes(const float* sphere, std::size_t count, const double* low, const double* extent,
                 std::uint64_t* code) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const hn::RebindToSigned<decltype(d)> di;
  const hn::RebindToUnsigned<decltype(d)> du;
  const std::size_t lanes = hn::Lanes(d);
  constexpr std::size_t max_lanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN float padded[4 * max_lanes];
  HWY_ALIGN std::uint64_t out[max_lanes];
  for (std::size_t start = 0; start < count; start += lanes) {
    const std::size_t n = std::min(lanes, count - start);
    const float* at = sphere + 4 * start;
    if (n < lanes) {  // the last lanes repeat the last light
      for (std::size_t i = 0; i < 4 * lanes; ++i) padded[i] = at[std::min(i, 4 * n - 4 + i % 4)];
      at = padded;
    }
    hn::Vec<decltype(df)> centre[3], range;
    hn::LoadInterleaved4(df, at, centre[0], centre[1], centre[2], range);
    auto result = hn::Zero(du);
    for (int k = 0; k < 3; ++k) {
      const auto t =
          hn::Div(hn::Sub(hn::PromoteTo(d, centre[k]), hn::Set(d, low[k])), hn::Set(d, extent[k]));
      const auto q =
          hn::Min(hn::Max(hn::Mul(t, hn::Set(d, 2097152.0)), hn::Zero(d)), hn::Set(d, 2097151.0));
      const auto spread = spread_every_third(du, hn::BitCast(du, hn::ConvertTo(di, q)));
      result = hn::Or(result, hn::ShiftLeftSame(spread, 2 - k));
    }
    if (n == lanes) {
      hn::StoreU(result, du, code + start);
    } else {
      hn::Store(result, du, out);
      std::copy(out, out + n, code + start);
    }
  }
}

// round_down / round_up of reference/lightassign/light_bvh.cpp on lanes: the nearest float, then
// one float step down (up) where it lies above (below) x. A step toward -inf adds one to the bits
// of a negative float and takes one from a positive one (toward +inf the opposite); a float
// rounded from a double is never a zero on the wrong side, nor a NaN from a finite x.
template <bool down, class D>
HWY_INLINE hn::Vec<hn::Rebind<float, D>> round_outwards(D d, hn::Vec<D> x) {
  const hn::Rebind<float, D> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  const hn::RebindToUnsigned<D> du64;
  const auto f = hn::DemoteTo(df, x);
  const auto back = hn::PromoteTo(d, f);
  const auto off = down ? hn::Gt(back, x) : hn::Lt(back, x);
  const auto fix = hn::TruncateTo(du, hn::BitCast(du64, hn::VecFromMask(d, off)));
  const auto bits = hn::BitCast(du, f);
  const auto negative = hn::ShiftRight<31>(bits);  // 1 for a negative float
  const auto two_negative = hn::Add(negative, negative);
  // down: +1 negative, -1 positive (2n - 1); up: -1 negative, +1 positive (1 - 2n).
  const auto step =
      down ? hn::Sub(two_negative, hn::Set(du, 1u)) : hn::Sub(hn::Set(du, 1u), two_negative);
  return hn::BitCast(df, hn::Add(bits, hn::And(step, fix)));
}

void LeafNodeBoxes(const LightBvhLanes& bvh, std::size_t first, std::size_t count,
                   BoxArrays& level) {
  // round_down and round_up are monotone: the least of the leaves' round_down(c - r) is
  // round_down of the least c - r (the greatest round_up likewise), so the node box needs no
  // leaf boxes.
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const std::size_t lanes = hn::Lanes(d);
  const std::size_t leaves = bvh.order.size();
  const auto infinity = hn::Set(d, std::numeric_limits<double>::infinity());
  for (std::size_t node = first; node < first + count; ++node) {
    const std::size_t at = node * node_width, valid = std::min(leaves - at, node_width);
    auto low_x = infinity, low_y = infinity, low_z = infinity;
    auto high_x = hn::Neg(infinity), high_y = high_x, high_z = high_x;
    for (std::size_t i = 0; i < valid; i += lanes) {
      const auto in = hn::FirstN(d, valid - i);
      const auto r = hn::PromoteTo(d, hn::LoadU(df, bvh.sphere[3].data() + at + i));
      auto extend = [&](int k, auto& low, auto& high) {
        const auto c = hn::PromoteTo(d, hn::LoadU(df, bvh.sphere[k].data() + at + i));
        low = hn::IfThenElse(in, hn::Min(low, hn::Sub(c, r)), low);
        high = hn::IfThenElse(in, hn::Max(high, hn::Add(c, r)), high);
      };
      extend(0, low_x, high_x);
      extend(1, low_y, high_y);
      extend(2, low_z, high_z);
    }
    HWY_ALIGN float out[HWY_MAX_BYTES / sizeof(double)];
    const decltype(low_x)* lows[3] = {&low_x, &low_y, &low_z};
    const decltype(low_x)* highs[3] = {&high_x, &high_y, &high_z};
    for (int k = 0; k < 3; ++k) {
      hn::Store(round_outwards<true>(d, hn::MinOfLanes(d, *lows[k])), df, out);
      level.min[k][node] = out[0];
      hn::Store(round_outwards<false>(d, hn::MaxOfLanes(d, *highs[k])), df, out);
      level.max[k][node] = out[0];
    }
  }
}

void NodeBoxes(const BoxArrays& children, std::size_t first, std::size_t count, BoxArrays& level) {
  const hn::CappedTag<float, node_width> d;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t node = first; node < first + count; ++node) {
    const std::size_t at = node * node_width;  // the padding holds empty boxes: min/max ignore it
    for (int k = 0; k < 3; ++k) {
      auto low = hn::LoadU(d, children.min[k].data() + at);
      auto high = hn::LoadU(d, children.max[k].data() + at);
      for (std::size_t i = lanes; i < node_width; i += lanes) {
        low = hn::Min(low, hn::LoadU(d, children.min[k].data() + at + i));
        high = hn::Max(high, hn::LoadU(d, children.max[k].data() + at + i));
      }
      level.min[k][node] = hn::GetLane(hn::MinOfLanes(d, low));
      level.max[k][node] = hn::GetLane(hn::MaxOfLanes(d, high));
    }
  }
}

// glm::dot of two dvec3: (x + y) + z of the products.
template <class V>
HWY_INLINE V dot3(const V x, const V y, const V z, const double* axis) {
  const hn::DFromV<V> d;
  return hn::Add(hn::Add(hn::Mul(x, hn::Set(d, axis[0])), hn::Mul(y, hn::Set(d, axis[1]))),
                 hn::Mul(z, hn::Set(d, axis[2])));
}

ListWork CullTileCandidates(const std::vector<RangedLight>& lights, const ViewFrame& frame,
                            const TileVolume& tile, const std::uint32_t* candidates,
                            std::size_t count, std::vector<std::uint32_t>& list) {
  ListWork w;
  w.light_tests = count;
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V near_depth = hn::Set(d, tile.near_depth), far_depth = hn::Set(d, tile.far_depth);
  const V origin_length = hn::Set(d, tile.origin_length);
  const V rounding_margin = hn::Set(d, 0x1p-40);
  constexpr std::size_t max_lanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double centre[3][max_lanes], range[max_lanes];
  for (std::size_t start = 0; start < count; start += lanes) {
    const std::size_t n = std::min(lanes, count - start);
    // The candidates' spheres (one cache line of the light each); lanes past them repeat the last.
    for (std::size_t i = 0; i < lanes; ++i) {
      const RangedLight& light = lights[candidates[start + std::min(i, n - 1)]];
      for (int k = 0; k < 3; ++k) centre[k][i] = double(light.centre[k]);
      range[i] = double(light.range);
    }
    const V cx = hn::Load(d, centre[0]), cy = hn::Load(d, centre[1]), cz = hn::Load(d, centre[2]);
    const V radius = hn::Load(d, range);
    // ViewFrustum::to_view and glm::length(centre).
    const V dx = hn::Sub(cx, hn::Set(d, frame.origin[0]));
    const V dy = hn::Sub(cy, hn::Set(d, frame.origin[1]));
    const V dz = hn::Sub(cz, hn::Set(d, frame.origin[2]));
    const V vx = dot3(dx, dy, dz, frame.right);
    const V vy = dot3(dx, dy, dz, frame.up);
    const V vz = dot3(dx, dy, dz, frame.forward);
    const V centre_length =
        hn::Sqrt(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)));
    // ViewFrustum::sphere_may_meet, operation by operation.
    const V margin =
        hn::Mul(rounding_margin,
                hn::Add(hn::Add(hn::Add(centre_length, origin_length), radius), far_depth));
    const V reach = hn::Add(radius, margin);
    const V minus_reach = hn::Neg(reach);
    // Lanes past the candidates count as rejected; a block stops at the first test that leaves
    // none of its lanes.
    auto rejected = hn::Or(
        hn::Not(hn::FirstN(d, n)),
        hn::Or(hn::Lt(vz, hn::Sub(near_depth, reach)), hn::Gt(vz, hn::Add(far_depth, reach))));
    const V along[4] = {vx, hn::Neg(vx), hn::Neg(vy), vy};
    for (int p = 0; p < 4 && !hn::AllTrue(d, rejected); ++p) {
      const V distance = hn::Div(hn::Sub(along[p], hn::Mul(hn::Set(d, tile.slope[p]), vz)),
                                 hn::Set(d, tile.norm[p]));
      rejected = hn::Or(rejected, hn::Lt(distance, minus_reach));
    }
    if (hn::AllTrue(d, rejected)) continue;
    const std::uint64_t lane_mask = n >= 64 ? ~0ull : (1ull << n) - 1;
    std::uint64_t passing = ~lane_bits(d, rejected) & lane_mask;
    std::uint64_t inside = 0, outside = 0;
    sphere_box_filter(d, cx, cy, cz, hn::Mul(radius, radius), tile.box, inside, outside);
    for (; passing != 0; passing &= passing - 1) {
      const int i = std::countr_zero(passing);
      const std::uint32_t light = candidates[start + std::size_t(i)];
      bool meets = (inside >> i) & 1u;
      if (!meets && !((outside >> i) & 1u))
        meets = geometry::sphere_meets_box_exact(lights[light].centre, lights[light].range,
                                                 tile.box.min, tile.box.max);
      if (meets) list.push_back(light);
    }
  }
  return w;
}

void RowClusterKeys(const ViewFrame& frame, const SliceTable& slices, int slice_shift,
                    const std::uint32_t* tile_key_of_x, std::uint32_t row_pixel,
                    const std::uint32_t* index, const float* x, const float* y, const float* z,
                    std::size_t count, std::uint32_t* key, double& deepest) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const hn::Rebind<std::int32_t, decltype(d)> di;
  const hn::Rebind<std::uint32_t, decltype(d)> du;
  const hn::RebindToSigned<decltype(d)> dl;
  const std::size_t lanes = hn::Lanes(d);
  const auto ox = hn::Set(d, frame.origin[0]), oy = hn::Set(d, frame.origin[1]),
             oz = hn::Set(d, frame.origin[2]);
  const auto inverse_near = hn::Set(d, slices.inverse_near);
  const auto one = hn::Set(d, 1.0);
  const auto inverse_log_base = hn::Set(df, slices.inverse_log_base);
  const auto last = hn::Set(di, std::int32_t(slices.last));
  const auto first_pixel = hn::Set(du, row_pixel);
  const bool tabled = !slices.low.empty();
  auto deepest_lanes = hn::Zero(d);
  constexpr std::size_t max_lanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double depth[max_lanes];
  HWY_ALIGN std::uint32_t tile_key[max_lanes];
  std::size_t i = 0;
  for (; i + lanes <= count; i += lanes) {
    // ViewFrustum::depth: dot(p - eye, forward) in glm's order.
    const auto dx = hn::Sub(hn::PromoteTo(d, hn::LoadU(df, x + i)), ox);
    const auto dy = hn::Sub(hn::PromoteTo(d, hn::LoadU(df, y + i)), oy);
    const auto dz = hn::Sub(hn::PromoteTo(d, hn::LoadU(df, z + i)), oz);
    const auto depth_v = dot3(dx, dy, dz, frame.forward);
    // std::max(deepest, depth): a NaN depth leaves it.
    deepest_lanes = hn::IfThenElse(hn::Lt(deepest_lanes, depth_v), depth_v, deepest_lanes);
    // The guess: floor of eq. 2's quotient in float (the ratio kept >= 1: depths before the near
    // plane and NaN guess slice 0), clamped to the slices.
    const auto ratio = hn::DemoteTo(df, hn::Max(hn::Mul(depth_v, inverse_near), one));
    const auto quotient = hn::Mul(hn::Log(df, ratio), inverse_log_base);
    const auto guess = hn::Min(hn::Max(hn::ConvertTo(di, hn::Floor(quotient)), hn::Zero(di)), last);
    const auto xs = hn::BitCast(di, hn::Sub(hn::LoadU(du, index + i), first_pixel));
    const auto tile = hn::GatherIndex(du, tile_key_of_x, xs);
    hn::StoreU(hn::Or(tile, hn::ShiftLeftSame(hn::BitCast(du, guess), slice_shift)), du, key + i);
    std::uint64_t unsure = ~0ull;
    if (tabled) {
      const auto at = hn::PromoteTo(dl, guess);
      const auto sure = hn::And(hn::Ge(depth_v, hn::GatherIndex(d, slices.low.data(), at)),
                                hn::Lt(depth_v, hn::GatherIndex(d, slices.high.data(), at)));
      if (hn::AllTrue(d, sure)) continue;
      unsure = ~lane_bits(d, sure);
    }
    hn::Store(depth_v, d, depth);
    hn::Store(tile, du, tile_key);
    for (std::size_t j = 0; j < lanes; ++j)
      if ((unsure >> j) & 1u)
        key[i + j] = tile_key[j] | slices.grid->slice_of(depth[j]) << slice_shift;
  }
  HWY_ALIGN double lane_deepest[max_lanes];
  hn::Store(deepest_lanes, d, lane_deepest);
  for (std::size_t j = 0; j < lanes; ++j) deepest = std::max(deepest, lane_deepest[j]);
  for (; i < count; ++i) {
    const double depth_i = (((double(x[i]) - frame.origin[0]) * frame.forward[0] +
                             (double(y[i]) - frame.origin[1]) * frame.forward[1]) +
                            (double(z[i]) - frame.origin[2]) * frame.forward[2]);
    deepest = std::max(deepest, depth_i);
    key[i] = tile_key_of_x[index[i] - row_pixel] | slices.grid->slice_of(depth_i) << slice_shift;
  }
}

// NOLINTNEXTLINE(google-readability-namespace-comments)
}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd {

HWY_EXPORT(QueryLightBvh);
HWY_EXPORT(TestEveryLight);
HWY_EXPORT(MortonCodes);
HWY_EXPORT(LeafNodeBoxes);
HWY_EXPORT(NodeBoxes);
HWY_EXPORT(CullTileCandidates);
HWY_EXPORT(RowClusterKeys);

SliceTable::SliceTable(const ClusterGrid& grid)
    : grid(&grid),
      inverse_near(1.0 / grid.slice_near(0)),
      inverse_log_base(float(1.0 / std::log(grid.slice_base()))),
      last(std::uint32_t(grid.slices() - 1)) {
  // A table for any grid a 32-bit key and a sane near/far ratio give; beyond, slice_of decides.
  constexpr std::uint64_t most_slices = 1 << 16;
  if (grid.slices() > most_slices) return;
  constexpr double margin = 1e-10;
  const std::size_t slices = std::size_t(grid.slices());
  low.resize(slices);
  high.resize(slices);
  double next_near = grid.slice_near(0);
  for (std::size_t k = 0; k < slices; ++k) {
    const double near = next_near;
    next_near = grid.slice_near(k + 1);
    low[k] = k == 0 ? -std::numeric_limits<double>::infinity() : near * (1.0 + margin);
    high[k] = k == last ? std::numeric_limits<double>::infinity() : next_near * (1.0 - margin);
  }
}

void row_cluster_keys(const ViewFrame& frame, const SliceTable& slices, int slice_shift,
                      const std::uint32_t* tile_key_of_x, std::uint32_t row_pixel,
                      const std::uint32_t* index, const float* x, const float* y, const float* z,
                      std::size_t count, std::uint32_t* key, double& deepest) {
  HWY_DYNAMIC_DISPATCH(RowClusterKeys)
  (frame, slices, slice_shift, tile_key_of_x, row_pixel, index, x, y, z, count, key, deepest);
}

void morton_codes(const float* sphere, std::size_t count, const double* low, const double* extent,
                  std::uint64_t* code) {
  HWY_DYNAMIC_DISPATCH(MortonCodes)(sphere, count, low, extent, code);
}

void leaf_node_boxes(const LightBvhLanes& bvh, std::size_t first, std::size_t count,
                     BoxArrays& level) {
  HWY_DYNAMIC_DISPATCH(LeafNodeBoxes)(bvh, first, count, level);
}

void node_boxes(const BoxArrays& children, std::size_t first, std::size_t count, BoxArrays& level) {
  HWY_DYNAMIC_DISPATCH(NodeBoxes)(children, first, count, level);
}

ListWork test_every_light(const LightBvhLanes& bvh, const Aabb& box,
                          std::vector<std::uint32_t>& list) {
  return HWY_DYNAMIC_DISPATCH(TestEveryLight)(bvh, box, list);
}

ListWork query_light_bvh(const LightBvhLanes& bvh, const Aabb& box,
                         std::vector<std::uint32_t>& list) {
  return HWY_DYNAMIC_DISPATCH(QueryLightBvh)(bvh, box, list);
}

ListWork cull_tile_candidates(const std::vector<RangedLight>& lights, const ViewFrame& frame,
                              const TileVolume& tile, const std::uint32_t* candidates,
                              std::size_t count, std::vector<std::uint32_t>& list) {
  return HWY_DYNAMIC_DISPATCH(CullTileCandidates)(lights, frame, tile, candidates, count, list);
}

ViewFrame::ViewFrame(const Camera& camera) {
  // The frame the view samples were cast in (ViewFrustum's too).
  const CameraFrame frame = camera_frame(camera);
  for (int k = 0; k < 3; ++k) {
    origin[k] = frame.origin[k];
    right[k] = frame.right[k];
    up[k] = frame.up[k];
    forward[k] = frame.forward[k];
  }
}

}  // namespace shadowcts::simd
#endif  // HWY_ONCE
