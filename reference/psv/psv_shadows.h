#pragma once
// Hard shadows of a case with partitioned shadow volumes: builds the TOP tree once, then locates
// every regular view sample with one of the four queries of Mora 2016.
#include <cstdint>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::psv {

enum class QueryKind {
  stack,      // PSV: Algorithm 1
  depth,      // D-PSV: Algorithm 1 with the depth test
  stackless,  // D-Stackless: Algorithm 3
  hybrid,     // D-Hybrid: short stack, stackless when it is full
};

struct PsvOptions {
  QueryKind query = QueryKind::hybrid;
  std::uint32_t stack_capacity = 12;  // stack and hybrid queries
  // Seed of the insertion order (Case::parameters.seed when run through the registry).
  std::uint64_t seed = 1;
};

struct PsvResult {
  // Per view sample, 1 = shadowed: some caster other than its receiver meets its segment (ray)
  // strictly on the light's side of the receiver's plane (the receiver half-space rule).
  std::vector<std::uint8_t> shadowed;
  std::vector<std::uint32_t> nodes_visited;  // per view sample (0 for non-regular samples)
  // In this order: triangles_inserted, triangles_culled_front_facing, triangles_culled_flat,
  // triangles_dropped_in_shadow, tree_nodes, tree_height, queries, nodes_visited_total,
  // nodes_visited_max, stack_capacity, stack_high_water, stack_overflows, hybrid_switches,
  // exact_plane_tests (plane tests of the build and the queries that the float filter could not
  // decide and an exact predicate answered).
  Counters counters;
  // "build" (insertion order, TOP tree, query context) and "query" (the per-sample queries).
  PhaseTimes phase_ms;
};

// A stack query that overflows its stack has no answer; that sample is counted in
// stack_overflows and answered again by the stackless query (its nodes count too), so the mask is
// never wrong. Runs on c.parameters.threads threads; the result and the counters do not depend on
// the thread count. Throws InputError when the case has no point or directional light.
PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples, const PsvOptions& options);

}  // namespace shadowcts::psv
