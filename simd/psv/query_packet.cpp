// The packet queries of the simd psv (query_packet.h): the one translation unit of the port that
// Highway compiles once per target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/psv/query_packet.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "reference/psv/top_tree_depth.h"
#include "simd/psv/query_hybrid.h"
#include "simd/psv/query_packet.h"
#include "simd/psv/query_stack.h"
#include "simd/psv/query_stackless.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::psv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class D, class M>
HWY_INLINE std::uint32_t lane_bits(D d, M mask) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  return bytes[0];
}

// The tests of `node` for every lane of the packet, with the reference's operations in the
// reference's order (geometry/plane_filter.h): each IEEE operation rounds once in a vector lane
// as in a scalar, so the wedge decisions agree with the reference's to the bit.
NodeTests node_tests(const QueryTree& q, std::uint32_t node, const Packet& packet) {
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  const ref::TopNode& n = q.tree.nodes[node];
  const bool capping = ref::is_capping_node(node);
  const auto a = hn::Set(d, double(n.plane[0])), b = hn::Set(d, double(n.plane[1])),
             c = hn::Set(d, double(n.plane[2])), offset = hn::Set(d, double(n.plane[3]));
  const auto bound = hn::Set(d, q.planes.node_bound(n, capping));
  const bool has_intersection = n.intersection != ref::no_node;
  const bool wedge_test = has_intersection && !capping;
  const geometry::PlaneFilter& filter = q.planes.exact().filter();
  // The per-point error bound's terms that depend on the node only.
  const double aa = std::fabs(double(n.plane[0])), ab = std::fabs(double(n.plane[1])),
               ac = std::fabs(double(n.plane[2])), ad = std::fabs(double(n.plane[3]));
  const double spread = ((aa + ab) + ac) * filter.scene_bound;
  const auto wedge = hn::Set(d, double(n.wedge));
  const bool depth_of_intersection = has_intersection && q.depth_test;
  const auto intersection_depth =
      hn::Set(d, depth_of_intersection ? double(ref::volume_depth(q.tree, n.intersection)) : 0.0);
  const bool depth_of_positive = n.positive != ref::no_node && q.depth_test;
  const auto positive_depth =
      hn::Set(d, depth_of_positive ? double(ref::volume_depth(q.tree, n.positive)) : 0.0);

  NodeTests tests;
  for (std::size_t j = 0; j < packet.size; j += lanes) {
    const auto x = hn::Load(d, packet.x + j), y = hn::Load(d, packet.y + j),
               z = hn::Load(d, packet.z + j), depth = hn::Load(d, packet.light_depth + j);
    const auto value =
        hn::Add(hn::Add(hn::Add(hn::Mul(a, x), hn::Mul(b, y)), hn::Mul(c, z)), offset);
    tests.positive |= lane_bits(d, hn::Gt(value, bound)) << j;
    tests.negative |= lane_bits(d, hn::Lt(value, hn::Neg(bound))) << j;
    if (has_intersection) {
      auto visits = hn::FirstN(d, lanes);
      if (wedge_test) {
        const auto px = hn::Abs(x), py = hn::Abs(y), pz = hn::Abs(z);
        const auto magnitude = hn::Add(
            hn::Add(hn::Add(hn::Add(hn::Mul(hn::Set(d, aa), px), hn::Mul(hn::Set(d, ab), py)),
                            hn::Mul(hn::Set(d, ac), pz)),
                    hn::Set(d, ad)),
            hn::Set(d, spread));
        const auto subnormal =
            hn::Mul(hn::Set(d, 0x1p-149), hn::Add(hn::Add(hn::Add(px, py), pz), hn::Set(d, 1.0)));
        const auto error = hn::Add(hn::Add(hn::Mul(hn::Set(d, 0x1p-22), magnitude), subnormal),
                                   hn::Set(d, filter.edge_extra_error));
        const auto outside = hn::Sub(hn::Abs(value), error);
        const auto limit = q.directional ? wedge : hn::Mul(wedge, depth);
        visits = hn::Not(hn::Gt(outside, limit));
      }
      if (depth_of_intersection) visits = hn::AndNot(hn::Lt(depth, intersection_depth), visits);
      tests.visits_intersection |= lane_bits(d, visits) << j;
    }
    if (depth_of_positive)
      tests.positive_skipped |= lane_bits(d, hn::Lt(depth, positive_depth)) << j;
  }
  const std::uint32_t all = (1u << packet.size) - 1u;
  tests.positive &= all;
  tests.negative &= all;
  tests.visits_intersection &= all;
  tests.positive_skipped &= all;
  return tests;
}

// Runs `kind` for the lanes of `active` until each has its answer.
void run_lanes(const QueryTree& q, ref::QueryKind kind, std::uint32_t capacity, Packet& packet,
               std::uint32_t active) {
  Worklist work;
  // An empty tree, or a sample closer to the light than every triangle, is lit without a visit.
  for_each_lane(active, [&](std::uint32_t i) {
    packet.switched_at[i] = ref::no_node;
    packet.stack_size[i] = 0;
    if (q.tree.root == ref::no_node || q.exact.skipped_by_depth(q.tree.root, packet.point[i]))
      packet.answer[i] = ref::QueryAnswer::lit;
    else
      work.add(q.tree.root, false, 1u << i);
  });
  while (!work.empty()) {
    const Group group = work.take();
    const NodeTests tests = node_tests(q, group.node, packet);
    switch (kind) {
      case ref::QueryKind::stack:
      case ref::QueryKind::depth:
        step_stack(q, group, tests, capacity, packet, work);
        break;
      case ref::QueryKind::stackless:
        step_stackless(q, group, tests, packet, work);
        break;
      case ref::QueryKind::hybrid:
        step_hybrid(q, group, tests, capacity, packet, work);
        break;
    }
  }
}

void QueryPackets(const QueryTree& q, const ref::PsvOptions& options, const HardShadowLight& light,
                  const RegularSamples& samples, std::size_t begin, std::size_t end,
                  std::uint32_t packet_size, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                  ref::PsvQueryTotals& totals) {
  Packet packet;
  for (std::size_t first = begin; first < end; first += packet_size) {
    packet.size = std::uint32_t(std::min<std::size_t>(packet_size, end - first));
    for (std::uint32_t i = 0; i < max_packet; ++i) {
      // Lanes past the packet's end repeat its first sample: their tests are computed and unused.
      const std::size_t s = first + (i < packet.size ? i : 0);
      ref::QueryPoint& point = packet.point[i];
      point = ref::QueryPoint();
      point.position = glm::dvec3(samples.position(s));
      point.receiver = samples.receiver[s];
      point.light_depth = ref::sample_light_depth(light, point.position);
      packet.x[i] = point.position.x;
      packet.y[i] = point.position.y;
      packet.z[i] = point.position.z;
      packet.light_depth[i] = point.light_depth;
      packet.work[i] = ref::QueryWork();
    }
    const std::uint32_t all = (1u << packet.size) - 1u;
    run_lanes(q, options.query, options.stack_capacity, packet, all);
    std::uint32_t overflowed = 0;
    for (std::uint32_t i = 0; i < packet.size; ++i)
      if (packet.answer[i] == ref::QueryAnswer::stack_overflow) overflowed |= 1u << i;
    if (overflowed != 0) {
      totals.stack_overflows += std::uint64_t(std::popcount(overflowed));
      run_lanes(q, ref::QueryKind::stackless, 0, packet, overflowed);
    }
    for (std::uint32_t i = 0; i < packet.size; ++i) {
      const ref::QueryWork& work = packet.work[i];
      shadowed[first + i - begin] = packet.answer[i] == ref::QueryAnswer::shadowed ? 1 : 0;
      nodes_visited[first + i - begin] = std::uint32_t(work.nodes_visited);
      ++totals.queries;
      totals.nodes_visited_total += work.nodes_visited;
      totals.nodes_visited_max = std::max(totals.nodes_visited_max, work.nodes_visited);
      totals.stack_high_water =
          std::max<std::uint64_t>(totals.stack_high_water, work.stack_high_water);
      totals.hybrid_switches += work.hybrid_switches;
    }
  }
}

const char* QueryTarget() {
  return hwy::TargetName(HWY_TARGET);
}

}  // namespace shadowcts::simd::psv::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::psv {

HWY_EXPORT(QueryPackets);
HWY_EXPORT(QueryTarget);

void query_packets(const QueryTree& q, const ref::PsvOptions& options, const HardShadowLight& light,
                   const RegularSamples& samples, std::size_t begin, std::size_t end,
                   std::uint32_t packet, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                   ref::PsvQueryTotals& totals) {
  HWY_DYNAMIC_DISPATCH(QueryPackets)
  (q, options, light, samples, begin, end, packet, shadowed, nodes_visited, totals);
}

std::string query_target() {
  return HWY_DYNAMIC_DISPATCH(QueryTarget)();
}

}  // namespace shadowcts::simd::psv
#endif  // HWY_ONCE
