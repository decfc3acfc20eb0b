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

#include <glm/geometric.hpp>

#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/geometry/sphere_box.h"
#include "simd/lightassign/lightassign_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

constexpr std::size_t node_width = LightBvh::branching;  // 32

// Bit i set for lane i of mask m (at most 64 lanes).
template <class D, class M>
HWY_INLINE std::uint64_t mask_bits(D d, M m) {
  std::uint8_t bytes[16] = {};
  hn::StoreMaskBits(d, m, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof(bits));
  return bits;
}

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
    bits |= mask_bits(d, m) << i;
  }
  return std::uint32_t(bits);
}

// LightBvh::overlap(leaf box j, box) for the `count` (<= 32) leaf boxes at `boxes` (6 floats
// each), gathered in lanes, as bits.
HWY_INLINE std::uint32_t leaf_overlap_bits(const float* boxes, std::size_t count, const Aabb& box) {
  const hn::CappedTag<float, node_width> d;
  const hn::RebindToSigned<decltype(d)> di;
  const std::size_t lanes = hn::Lanes(d);
  // Offsets of leaf j's box, lanes past `count` reading the last leaf (and masked off).
  HWY_ALIGN std::int32_t offset[node_width];
  for (std::size_t j = 0; j < node_width; ++j) offset[j] = std::int32_t(6 * std::min(j, count - 1));
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < count; i += lanes) {
    const auto at = hn::Load(di, offset + i);
    auto m = hn::FirstN(d, count - i);
    for (int k = 0; k < 3; ++k)
      m = hn::And(m,
                  hn::And(hn::Le(hn::GatherIndex(d, boxes + k, at), hn::Set(d, box.max[k])),
                          hn::Le(hn::Set(d, box.min[k]), hn::GatherIndex(d, boxes + 3 + k, at))));
    bits |= mask_bits(d, m) << i;
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
  inside = mask_bits(d, hn::Lt(hn::Add(distance2, error), r2));
  outside = mask_bits(d, hn::Gt(hn::Sub(distance2, error), r2));
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
  const hn::ScalableTag<double> dd;
  const std::size_t dlanes = hn::Lanes(dd);
  const std::uint64_t dlane_mask = dlanes >= 64 ? ~0ull : (1ull << dlanes) - 1;
  while (size > 0) {
    const Entry e = stack[--size];
    const std::size_t first = std::size_t(e.node) * node_width;
    if (e.level == 0) {
      const std::size_t count = std::min(first + node_width, bvh.leaf_count) - first;
      w.nodes_tested += count;
      const std::uint32_t overlapping = leaf_overlap_bits(bvh.leaf_boxes + 6 * first, count, box);
      if (overlapping == 0) continue;
      w.light_tests += std::uint64_t(std::popcount(overlapping));
      // The filter on the lanes of overlapping leaves (their spheres gathered, the rest zero).
      HWY_ALIGN double centre[3][node_width] = {}, range2[node_width] = {};
      for (std::uint32_t bits = overlapping; bits != 0; bits &= bits - 1) {
        const int i = std::countr_zero(bits);
        const RangedLight& light = bvh.lights[bvh.order[first + std::size_t(i)]];
        for (int k = 0; k < 3; ++k) centre[k][i] = double(light.centre[k]);
        range2[i] = double(light.range) * double(light.range);  // exact: 48 bits
      }
      std::uint64_t inside = 0, outside = 0;
      for (std::size_t i = 0; i < count; i += dlanes) {
        if (((overlapping >> i) & dlane_mask) == 0) continue;
        std::uint64_t in_bits = 0, out_bits = 0;
        sphere_box_filter(dd, hn::Load(dd, centre[0] + i), hn::Load(dd, centre[1] + i),
                          hn::Load(dd, centre[2] + i), hn::Load(dd, range2 + i), box, in_bits,
                          out_bits);
        inside |= (in_bits & dlane_mask) << i;
        outside |= (out_bits & dlane_mask) << i;
      }
      for (std::uint32_t bits = overlapping; bits != 0; bits &= bits - 1) {
        const int i = std::countr_zero(bits);
        const std::uint32_t index = bvh.order[first + std::size_t(i)];
        bool meets = (inside >> i) & 1u;
        if (!meets && !((outside >> i) & 1u))
          meets = geometry::sphere_meets_box_exact(bvh.lights[index].centre,
                                                   bvh.lights[index].range, box.min, box.max);
        if (meets) list.push_back(index);
      }
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
    std::uint64_t passing = ~mask_bits(d, rejected) & lane_mask;
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

void SlicesOf(const ClusterGrid& grid, const double* depth, std::size_t count,
              std::uint32_t* slice) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  // slice_of: k = floor(log(depth / near) / log(base)); near_0 = near exactly (base^0 = 1).
  const double near = grid.slice_near(0);
  const auto near_v = hn::Set(d, near);
  const auto log_base = hn::Set(d, std::log(grid.slice_base()));
  const auto margin = hn::Set(d, 1e-10);
  const auto one = hn::Set(d, 1.0);
  const double last = double(grid.slices() - 1);
  HWY_ALIGN double floors[HWY_MAX_BYTES / sizeof(double)];
  std::size_t i = 0;
  for (; i + lanes <= count; i += lanes) {
    const auto depth_v = hn::LoadU(d, depth + i);
    const auto t = hn::Div(hn::Log(d, hn::Div(depth_v, near_v)), log_base);
    const auto nearest = hn::Round(t);
    // Sure: the quotient is away from every integer, or the depth is before the near plane.
    const auto sure =
        hn::Or(hn::Not(hn::Gt(depth_v, near_v)),
               hn::Gt(hn::Abs(hn::Sub(t, nearest)), hn::Mul(margin, hn::Add(hn::Abs(t), one))));
    hn::Store(hn::Floor(t), d, floors);
    const std::uint64_t sure_bits = mask_bits(d, sure);
    for (std::size_t j = 0; j < lanes; ++j) {
      if (!((sure_bits >> j) & 1u))
        slice[i + j] = grid.slice_of(depth[i + j]);
      else if (!(depth[i + j] > near))
        slice[i + j] = 0;
      else
        slice[i + j] = std::uint32_t(std::min(floors[j], last));
    }
  }
  for (; i < count; ++i) slice[i] = grid.slice_of(depth[i]);
}

// NOLINTNEXTLINE(google-readability-namespace-comments)
}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd {

HWY_EXPORT(QueryLightBvh);
HWY_EXPORT(CullTileCandidates);
HWY_EXPORT(SlicesOf);

void slices_of(const ClusterGrid& grid, const double* depth, std::size_t count,
               std::uint32_t* slice) {
  HWY_DYNAMIC_DISPATCH(SlicesOf)(grid, depth, count, slice);
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
