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
#include "shadowcts/huge_pages.h"
#include "simd/lane_bits-inl.h"
#include "simd/psv/query_hybrid.h"
#include "simd/psv/query_packet.h"
#include "simd/psv/query_stack.h"
#include "simd/psv/query_stackless.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::psv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

// What the tests of a node need of the node.
struct NodeConstants {
  double a, b, c, offset, bound;
  double aa, ab, ac, ad, spread;  // the per-point error bound's terms that depend on the node only
  double wedge, edge_extra_error;
  bool has_intersection, wedge_test, directional;
  bool depth_of_intersection, depth_of_positive;
  double intersection_depth, positive_depth;
};

// The tests for the lanes of one vector of `d` from lane j on, with the reference's operations in
// the reference's order (geometry/plane_filter.h): each IEEE operation rounds once in a vector
// lane as in a scalar, so the wedge decisions agree with the reference's to the bit.
template <class D>
HWY_INLINE void test_lanes(D d, const NodeConstants& k, const Packet& packet, std::size_t j,
                           NodeTests& tests) {
  const auto x = hn::LoadU(d, packet.x + j), y = hn::LoadU(d, packet.y + j),
             z = hn::LoadU(d, packet.z + j), depth = hn::LoadU(d, packet.light_depth + j);
  const auto value =
      hn::Add(hn::Add(hn::Add(hn::Mul(hn::Set(d, k.a), x), hn::Mul(hn::Set(d, k.b), y)),
                      hn::Mul(hn::Set(d, k.c), z)),
              hn::Set(d, k.offset));
  const auto bound = hn::Set(d, k.bound);
  tests.positive |= lane_bits(d, hn::Gt(value, bound)) << j;
  tests.negative |= lane_bits(d, hn::Lt(value, hn::Neg(bound))) << j;
  if (k.has_intersection) {
    auto visits = hn::FirstN(d, hn::Lanes(d));
    if (k.wedge_test) {
      const auto px = hn::Abs(x), py = hn::Abs(y), pz = hn::Abs(z);
      const auto magnitude = hn::Add(
          hn::Add(hn::Add(hn::Add(hn::Mul(hn::Set(d, k.aa), px), hn::Mul(hn::Set(d, k.ab), py)),
                          hn::Mul(hn::Set(d, k.ac), pz)),
                  hn::Set(d, k.ad)),
          hn::Set(d, k.spread));
      const auto subnormal =
          hn::Mul(hn::Set(d, 0x1p-149), hn::Add(hn::Add(hn::Add(px, py), pz), hn::Set(d, 1.0)));
      const auto error = hn::Add(hn::Add(hn::Mul(hn::Set(d, 0x1p-22), magnitude), subnormal),
                                 hn::Set(d, k.edge_extra_error));
      const auto outside = hn::Sub(hn::Abs(value), error);
      const auto wedge = hn::Set(d, k.wedge);
      const auto limit = k.directional ? wedge : hn::Mul(wedge, depth);
      visits = hn::Not(hn::Gt(outside, limit));
    }
    if (k.depth_of_intersection)
      visits = hn::AndNot(hn::Lt(depth, hn::Set(d, k.intersection_depth)), visits);
    tests.visits_intersection |= lane_bits(d, visits) << j;
  }
  if (k.depth_of_positive)
    tests.positive_skipped |= lane_bits(d, hn::Lt(depth, hn::Set(d, k.positive_depth))) << j;
}

// The tests of `node` for the lanes of the group (bits of other lanes are left unspecified).
NodeTests node_tests(const QueryTree& q, std::uint32_t node, std::uint32_t lanes_of_group,
                     const Packet& packet) {
  const ref::TopNode& n = q.tree.nodes[node];
  const bool capping = ref::is_capping_node(node);
  NodeConstants k;
  k.a = double(n.plane[0]);
  k.b = double(n.plane[1]);
  k.c = double(n.plane[2]);
  k.offset = double(n.plane[3]);
  k.bound = q.planes.node_bound(n, capping);
  const geometry::PlaneFilter& filter = q.planes.exact().filter();
  k.aa = std::fabs(k.a);
  k.ab = std::fabs(k.b);
  k.ac = std::fabs(k.c);
  k.ad = std::fabs(k.offset);
  k.spread = ((k.aa + k.ab) + k.ac) * filter.scene_bound;
  k.wedge = double(n.wedge);
  k.edge_extra_error = filter.edge_extra_error;
  k.has_intersection = n.intersection != ref::no_node;
  k.wedge_test = k.has_intersection && !capping;
  k.directional = q.directional;
  k.depth_of_intersection = k.has_intersection && q.depth_test;
  k.intersection_depth =
      k.depth_of_intersection ? double(ref::volume_depth(q.tree, n.intersection)) : 0.0;
  k.depth_of_positive = n.positive != ref::no_node && q.depth_test;
  k.positive_depth = k.depth_of_positive ? double(ref::volume_depth(q.tree, n.positive)) : 0.0;

  NodeTests tests;
  if (std::has_single_bit(lanes_of_group)) {
    // A lone lane (frequent where the samples' paths part, as under foliage): one-lane vectors.
    test_lanes(hn::CappedTag<double, 1>(), k, packet, std::size_t(std::countr_zero(lanes_of_group)),
               tests);
    return tests;
  }
  const hn::ScalableTag<double> d;
  const std::size_t lanes = hn::Lanes(d);
  const std::uint32_t vector_lanes = lanes >= 32 ? ~0u : (1u << lanes) - 1u;
  for (std::size_t j = 0; j < packet.size; j += lanes)
    if (((lanes_of_group >> j) & vector_lanes) != 0) test_lanes(d, k, packet, j, tests);
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
    const NodeTests tests = node_tests(q, group.node, group.lanes, packet);
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
                  const RegularSamples& samples, const Packets& packets, std::size_t first_packet,
                  std::size_t last_packet, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                  ref::PsvQueryTotals& totals) {
  Packet packet;
  for (std::size_t k = first_packet; k < last_packet; ++k) {
    const std::uint32_t* lane_sample = packets.sample.data() + packets.begin[k];
    packet.size = packets.begin[k + 1] - packets.begin[k];
    for (std::uint32_t i = 0; i < max_packet; ++i) {
      // Lanes past the packet's end repeat its first sample: their tests are computed and unused.
      const std::size_t s = lane_sample[i < packet.size ? i : 0];
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
      shadowed[lane_sample[i]] = packet.answer[i] == ref::QueryAnswer::shadowed ? 1 : 0;
      nodes_visited[lane_sample[i]] = std::uint32_t(work.nodes_visited);
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
                   const RegularSamples& samples, const Packets& packets, std::size_t first,
                   std::size_t last, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                   ref::PsvQueryTotals& totals) {
  HWY_DYNAMIC_DISPATCH(QueryPackets)
  (q, options, light, samples, packets, first, last, shadowed, nodes_visited, totals);
}

Packets tile_packets(const RegularSamples& samples, const std::vector<std::uint8_t>& queried,
                     std::uint32_t width, std::uint32_t packet_size) {
  constexpr std::uint32_t tile = 4;
  width = std::max<std::uint32_t>(width, 1);
  const std::uint64_t tiles_across = (width + tile - 1) / tile;
  // The queried samples with their tile (band of 4 rows, then column): one division each.
  // Reserved once and the tiles in huge pages: growing arrays take fresh pages, and each fresh
  // 4 KiB page is a fault (huge_pages.h).
  std::vector<std::uint32_t> kept;
  kept.reserve(samples.size());
  HugePageVector<std::uint64_t> tile_of;
  tile_of.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!queried[i]) continue;
    const std::uint32_t pixel = samples.index[i], y = pixel / width;
    kept.push_back(std::uint32_t(i));
    tile_of.push_back(std::uint64_t(y / tile) * tiles_across + (pixel - y * width) / tile);
  }
  Packets packets;
  packets.sample.resize(kept.size());
  HugePageVector<std::uint64_t> sorted_tile(kept.size());
  // The samples are in pixel order, so a band is a run of them: within it, a counting sort by
  // tile column keeps each tile's samples in pixel order.
  std::vector<std::uint32_t> count(tiles_across + 1);
  for (std::size_t band = 0; band < kept.size();) {
    const std::uint64_t first_tile = tile_of[band] / tiles_across * tiles_across;
    std::size_t end = band;
    while (end < kept.size() && tile_of[end] / tiles_across * tiles_across == first_tile) ++end;
    std::fill(count.begin(), count.end(), 0u);
    for (std::size_t k = band; k < end; ++k) ++count[tile_of[k] - first_tile + 1];
    for (std::uint64_t t = 0; t < tiles_across; ++t) count[t + 1] += count[t];
    for (std::size_t k = band; k < end; ++k) {
      const std::size_t at = band + count[tile_of[k] - first_tile]++;
      packets.sample[at] = kept[k];
      sorted_tile[at] = tile_of[k];
    }
    band = end;
  }
  for (std::size_t k = 0; k < packets.sample.size(); ++k)
    if (k == 0 || sorted_tile[k] != sorted_tile[k - 1] || k - packets.begin.back() == packet_size)
      packets.begin.push_back(std::uint32_t(k));
  packets.begin.push_back(std::uint32_t(packets.sample.size()));
  return packets;
}

std::string query_target() {
  return HWY_DYNAMIC_DISPATCH(QueryTarget)();
}

}  // namespace shadowcts::simd::psv
#endif  // HWY_ONCE
