// CasterBvh::visit_packet's traversal: box_may_meet for the packet's lanes in vector registers,
// compiled for every Highway target and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "oracles/caster_bvh_packet.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

#include <bit>
#include <cstdint>

#include "oracles/caster_bvh.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using Lanes = CasterBvh::QueryLanes;

// Bit l set iff box_may_meet(lane l's query, lo, hi, its padding): the same operations in the
// same order (two separate roundings per product, no fused multiply-add), lane by lane. Without
// `zeros` no lane has a zero direction component, and their handling is left out.
template <bool zeros>
HWY_INLINE std::uint32_t lanes_meeting(const Lanes& q, const float lo[3], const float hi[3]) {
  const hn::ScalableTag<double> d;
  const std::size_t n = hn::Lanes(d);
  const auto one = hn::Set(d, 1.0);
  const auto slack = hn::Set(d, 1.0 + 0x1p-48);
  std::uint32_t mask = 0;
  for (std::size_t base = 0; base < std::size_t(CasterBvh::packet_lanes); base += n) {
    auto tnear = hn::Zero(d);
    auto tfar = hn::Load(d, q.t_max + base);
    auto inside = hn::Eq(one, one);
    const auto padding = hn::Load(d, q.padding + base);
    for (int i = 0; i < 3; ++i) {
      const auto low = hn::Sub(hn::Set(d, double(lo[i])), padding);
      const auto high = hn::Add(hn::Set(d, double(hi[i])), padding);
      const auto o = hn::Load(d, q.origin[i] + base);
      const auto inverse = hn::Load(d, q.inverse_direction[i] + base);
      const auto t0 = hn::Mul(hn::Sub(low, o), inverse);
      const auto t1 = hn::Mul(hn::Sub(high, o), inverse);
      const auto swapped = hn::Gt(t0, t1);
      const auto t_in = hn::IfThenElse(swapped, t1, t0);
      const auto t_out = hn::IfThenElse(swapped, t0, t1);
      if constexpr (zeros) {
        // A zero component: the origin within [low, high] decides, the parameters stay.
        const auto zero = hn::Eq(hn::Load(d, q.zero[i] + base), one);
        inside = hn::And(inside, hn::Or(hn::Not(zero), hn::And(hn::Ge(o, low), hn::Le(o, high))));
        tnear = hn::IfThenElse(hn::AndNot(zero, hn::Lt(tnear, t_in)), t_in, tnear);
        tfar = hn::IfThenElse(hn::AndNot(zero, hn::Lt(t_out, tfar)), t_out, tfar);
      } else {
        tnear = hn::IfThenElse(hn::Lt(tnear, t_in), t_in, tnear);
        tfar = hn::IfThenElse(hn::Lt(t_out, tfar), t_out, tfar);
      }
    }
    const auto meets = hn::And(inside, hn::Le(tnear, hn::Mul(tfar, slack)));
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, meets, bits);
    mask |= (std::uint32_t(bits[0]) | std::uint32_t(bits[1]) << 8) << base;
  }
  return mask;
}

template <bool zeros>
void VisitLanesOf(const CasterBvh::Node* nodes, const CasterBvh::Node* leaf_boxes,
                  const std::uint32_t* triangles, const Lanes& q, int lanes,
                  CasterBvh::LaneVisitor visit, void* context) {
  std::uint32_t active = lanes >= 32 ? ~0u : (1u << lanes) - 1u;
  struct Entry {
    std::uint32_t node, lanes;
  };
  Entry stack[64];
  int depth = 0;
  stack[depth++] = {0, active};
  while (depth > 0) {
    const Entry entry = stack[--depth];
    std::uint32_t meeting = entry.lanes & active;
    if (meeting == 0) continue;
    const CasterBvh::Node& node = nodes[entry.node];
    meeting &= lanes_meeting<zeros>(q, node.lo, node.hi);
    if (meeting == 0) continue;
    if (node.count == 0) {
      stack[depth++] = {node.first_or_right, meeting};
      stack[depth++] = {entry.node + 1, meeting};  // left child first
      continue;
    }
    for (std::uint32_t slot = node.first_or_right; slot < node.first_or_right + node.count;
         ++slot) {
      std::uint32_t visiting = meeting & active;
      if (visiting == 0) break;
      if (node.count > 1)
        visiting &= lanes_meeting<zeros>(q, leaf_boxes[slot].lo, leaf_boxes[slot].hi);
      for (; visiting != 0; visiting &= visiting - 1) {
        const int lane = std::countr_zero(visiting);
        if (visit(context, lane, triangles[slot])) active &= ~(1u << lane);
      }
    }
  }
}

void VisitLanes(const CasterBvh::Node* nodes, const CasterBvh::Node* leaf_boxes,
                const std::uint32_t* triangles, const Lanes& q, int lanes,
                CasterBvh::LaneVisitor visit, void* context) {
  // Spare lanes repeat lane 0 (visit_packet), so every lane counts.
  bool zeros = false;
  for (int i = 0; i < 3; ++i)
    for (int l = 0; l < CasterBvh::packet_lanes; ++l) zeros = zeros || q.zero[i][l] != 0.0;
  if (zeros)
    VisitLanesOf<true>(nodes, leaf_boxes, triangles, q, lanes, visit, context);
  else
    VisitLanesOf<false>(nodes, leaf_boxes, triangles, q, lanes, visit, context);
}

}  // namespace shadowcts::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts {

HWY_EXPORT(VisitLanes);

void CasterBvh::visit_lanes(const QueryLanes& q, int lanes, LaneVisitor visit,
                            void* context) const {
  HWY_DYNAMIC_DISPATCH(VisitLanes)
  (nodes_.data(), leaf_boxes_.data(), triangles_.data(), q, lanes, visit, context);
}

}  // namespace shadowcts
#endif
