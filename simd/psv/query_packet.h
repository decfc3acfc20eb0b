#pragma once
// The regular samples located in the TOP tree packet by packet (query_context.h), the node tests
// in Highway lanes, dispatched to the best target at run time.
#include <cstdint>
#include <string>

#include "reference/psv/psv_shadows.h"
#include "shadowcts/prepared_scene.h"
#include "simd/psv/query_context.h"

namespace shadowcts::simd::psv {

// Per regular sample [begin, end) of `samples`, in packets of `packet` (1 to max_packet) lanes:
// shadowed (1) or lit (0) and the nodes visited; the totals of those queries are added to
// `totals` (a stack query that overflows is answered by the stackless query, as in the
// reference, and counted in stack_overflows).
void query_packets(const QueryTree& q, const ref::PsvOptions& options, const HardShadowLight& light,
                   const RegularSamples& samples, std::size_t begin, std::size_t end,
                   std::uint32_t packet, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
                   ref::PsvQueryTotals& totals);

// The Highway target the queries dispatch to here (e.g. "AVX3").
std::string query_target();

}  // namespace shadowcts::simd::psv
