#pragma once
// The regular samples located in the TOP tree packet by packet (query_context.h), the node tests
// in Highway lanes, dispatched to the best target at run time.
#include <cstdint>
#include <string>
#include <vector>

#include "reference/psv/psv_shadows.h"
#include "shadowcts/prepared_scene.h"
#include "simd/psv/query_context.h"

namespace shadowcts::simd::psv {

// The regular samples to query grouped into packets: the samples of a 4 x 4 pixel tile, at most
// `packet_size` (1 to max_packet) per packet; samples close on screen mostly take the same path
// down the tree. Packet k holds sample[begin[k] .. begin[k + 1]).
struct Packets {
  std::vector<std::uint32_t> sample;  // regular sample indices, tile by tile
  std::vector<std::uint32_t> begin;   // one more than the number of packets
};
// `queried`: per regular sample, whether it is queried (PsvBuild::reached).
Packets tile_packets(const RegularSamples& samples, const std::vector<std::uint8_t>& queried,
                     std::uint32_t width, std::uint32_t packet_size);

// Packets [first, last): per regular sample, shadowed (1) or lit (0) and the nodes visited; the
// totals of those queries are added to `totals` (a stack query that overflows is answered by the
// stackless query, as in the reference, and counted in stack_overflows).
void query_packets(const QueryTree& q, const ref::PsvOptions& options, const HardShadowLight& light,
                   const RegularSamples& samples, const Packets& packets, std::size_t first,
                   std::size_t last, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                   ref::PsvQueryTotals& totals);

// The Highway target the queries dispatch to here (e.g. "AVX3").
std::string query_target();

}  // namespace shadowcts::simd::psv
