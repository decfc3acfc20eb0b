#pragma once
// Hard shadows of a case with partitioned shadow volumes: builds the TOP tree once, then locates
// every regular view sample with one of the four queries of Mora 2016.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_batches.h"
#include "reference/psv/top_tree_build.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"
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
  // triangles_culled_out_of_reach, triangles_dropped_in_shadow, tree_nodes, tree_height,
  // queries (the regular samples queried), samples_out_of_reach (regular samples lit without a
  // query: PsvBuild::reached), nodes_visited_total, nodes_visited_max, stack_capacity,
  // stack_high_water, stack_overflows, hybrid_switches, exact_plane_tests (plane tests of the
  // build and the queries that the float filter could not decide and an exact predicate
  // answered).
  Counters counters;
  // "build" (insertion order, TOP tree, query context) and "query" (the per-sample queries).
  PhaseTimes phase_ms;
};

// The options of a registered variant name (psv_variants()); throws std::invalid_argument for
// another name. Every backend of psv registers the same variants.
PsvOptions psv_variant_options(const std::string& variant);
std::vector<std::string> psv_variants();

// The build phase: the light, the plane tests, the insertion order and the TOP tree. The GPU port
// queries this same tree (uploaded), so both backends share it.
struct PsvBuild {
  HardShadowLight light;
  std::unique_ptr<PlaneSide> planes;  // refers to c.triangles
  BuildStatistics statistics;
  TopTree tree;
  // Per regular sample (in view-sample order): 0 where no triangle of the insertion order can
  // meet its segment (CasterReach::samples_reached), so it is lit without a query.
  std::vector<std::uint8_t> reached;
};
// Throws InputError when the case has no point or directional light.
PsvBuild build_psv(const Case& c, const ViewSamples& samples, std::uint64_t seed);

// build_psv with the tree built from batches of `engine`'s descents (top_tree_batches.h): the
// same build, for a port whose descents run elsewhere (the device). `make_engine` receives the
// build's plane tests.
using DescentEngineFactory = std::function<std::unique_ptr<DescentEngine>(const PlaneSide&)>;
PsvBuild build_psv_in_batches(const Case& c, const ViewSamples& samples, std::uint64_t seed,
                              const DescentEngineFactory& make_engine, BatchWork& work);

// What the queries of all samples add up to (sums and maxima: independent of the partitioning).
struct PsvQueryTotals {
  std::uint64_t queries = 0, nodes_visited_total = 0, nodes_visited_max = 0, stack_high_water = 0,
                stack_overflows = 0, hybrid_switches = 0;
};
// PsvResult::counters in their order; exact_plane_tests: of the build and the queries.
Counters psv_counters(const PsvBuild& build, const PsvQueryTotals& totals,
                      const PsvOptions& options, std::uint64_t exact_plane_tests);

// A stack query that overflows its stack has no answer; that sample is counted in
// stack_overflows and answered again by the stackless query (its nodes count too), so the mask is
// never wrong. Runs on c.parameters.threads threads; the result and the counters do not depend on
// the thread count. Throws InputError when the case has no point or directional light.
PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples, const PsvOptions& options);

}  // namespace shadowcts::psv
