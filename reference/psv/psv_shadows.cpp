#include "reference/psv/psv_shadows.h"

#include "reference/closed_mesh_culling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/psv/plane_side.h"
#include "reference/psv/query_context.h"
#include "reference/psv/query_hybrid.h"
#include "reference/psv/query_stack.h"
#include "reference/psv/query_stackless.h"
#include "reference/psv/rule_culling.h"
#include "reference/psv/top_tree_build.h"
#include "reference/psv/top_tree_depth.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts::psv {
namespace {

double max_abs(const glm::vec3& v) {
  return std::max({std::fabs(double(v.x)), std::fabs(double(v.y)), std::fabs(double(v.z))});
}

// Bound on every coordinate the plane tests see: triangles, light, samples.
double coordinate_bound(const Case& c, const ViewSamples& samples) {
  double bound = c.scale();
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular) bound = std::max(bound, max_abs(s.position));
  return std::max(bound, 1e-30);
}

}  // namespace

PsvOptions psv_variant_options(const std::string& variant) {
  PsvOptions options;
  if (variant == "stack") {
    options.query = QueryKind::stack;
  } else if (variant == "stack32") {
    options.query = QueryKind::stack;
    options.stack_capacity = 32;
  } else if (variant == "depth") {
    options.query = QueryKind::depth;
  } else if (variant == "stackless") {
    options.query = QueryKind::stackless;
  } else if (variant == "hybrid") {
    options.query = QueryKind::hybrid;
  } else if (variant == "hybrid4") {
    // The smallest stack of the paper's Figure 9 sweep (4 to 48): on the built-in cases a stack
    // of 12 never fills (high water 8), so only this variant runs the stackless switch.
    options.query = QueryKind::hybrid;
    options.stack_capacity = 4;
  } else {
    throw std::invalid_argument("psv: unknown variant '" + variant + "'");
  }
  return options;
}

std::vector<std::string> psv_variants() {
  return {"stack", "stack32", "depth", "stackless", "hybrid", "hybrid4"};
}

namespace {

// The build up to the insertion order: light, plane tests, culling.
std::vector<std::uint32_t> prepare_build(const Case& c, const ViewSamples& samples,
                                         std::uint64_t seed, PsvBuild& build) {
  build.light = hard_shadow_light(c);
  check_receivers(c, samples);
  build.planes =
      std::make_unique<PlaneSide>(build.light, c.triangles, coordinate_bound(c, samples));
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> receivers;
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular) {
      x.push_back(s.position.x);
      y.push_back(s.position.y);
      z.push_back(s.position.z);
      receivers.push_back(s.receiver);
    }
  std::optional<CasterReach> reach;  // its grids are filled on oneTBB threads
  run_with_thread_limit(c.parameters.threads, [&] { reach.emplace(build.light, x, y, z); });
  std::vector<std::uint32_t> order =
      insertion_order(c, *build.planes,
                      culling_clear_of_segment_starts(c, samples, build.light,
                                                      meshes_safe_for_face_culling(c, samples)),
                      *reach, seed, build.statistics);
  run_with_thread_limit(c.parameters.threads, [&] {
    build.reached = reach->samples_reached(c.triangles, order, x, y, z, receivers);
  });
  build.statistics.samples_out_of_reach =
      std::uint64_t(std::count(build.reached.begin(), build.reached.end(), std::uint8_t(0)));
  return order;
}

}  // namespace

PsvBuild build_psv(const Case& c, const ViewSamples& samples, std::uint64_t seed) {
  PsvBuild build;
  const std::vector<std::uint32_t> order = prepare_build(c, samples, seed, build);
  build.tree = build_top_tree(c, *build.planes, order, build.statistics);
  return build;
}

PsvBuild build_psv_in_batches(const Case& c, const ViewSamples& samples, std::uint64_t seed,
                              const DescentEngineFactory& make_engine, BatchWork& work) {
  PsvBuild build;
  const std::vector<std::uint32_t> order = prepare_build(c, samples, seed, build);
  const std::unique_ptr<DescentEngine> engine = make_engine(*build.planes);
  build.tree = build_top_tree_in_batches(*build.planes, order, build.statistics, *engine, work);
  return build;
}

Counters psv_counters(const PsvBuild& build, const PsvQueryTotals& totals,
                      const PsvOptions& options, std::uint64_t exact_plane_tests) {
  const bool uses_stack = options.query != QueryKind::stackless;
  return {{"triangles_inserted", build.statistics.volumes},
          {"triangles_culled_front_facing", build.statistics.culled_front_facing},
          {"triangles_culled_flat", build.statistics.culled_flat},
          {"triangles_culled_out_of_reach", build.statistics.culled_out_of_reach},
          {"triangles_dropped_in_shadow", build.statistics.dropped_in_shadow},
          {"tree_nodes", build.tree.nodes.size()},
          {"tree_height", build.statistics.height},
          {"queries", totals.queries},
          {"samples_out_of_reach", build.statistics.samples_out_of_reach},
          {"nodes_visited_total", totals.nodes_visited_total},
          {"nodes_visited_max", totals.nodes_visited_max},
          {"stack_capacity", uses_stack ? options.stack_capacity : 0},
          {"stack_high_water", totals.stack_high_water},
          {"stack_overflows", totals.stack_overflows},
          {"hybrid_switches", totals.hybrid_switches},
          {"exact_plane_tests", exact_plane_tests}};
}

PsvResult psv_hard_shadows(const Case& c, const ViewSamples& samples, const PsvOptions& options) {
  PhaseClock clock;
  const PsvBuild build = build_psv(c, samples, options.seed);
  const HardShadowLight& light = build.light;
  const bool depth_test = options.query != QueryKind::stack;
  const QueryContext context(build.tree, *build.planes, depth_test);
  clock.lap(build_phase);

  PsvResult result;
  result.shadowed.assign(samples.samples.size(), 0);
  result.nodes_visited.assign(samples.samples.size(), 0);
  // Which view samples need a query: the regular samples some inserted triangle may reach.
  std::vector<std::uint8_t> needs_query(samples.samples.size(), 0);
  for (std::size_t i = 0, rank = 0; i < samples.samples.size(); ++i)
    if (samples.samples[i].sample_class == SampleClass::regular)
      needs_query[i] = build.reached[rank++];
  std::atomic<std::uint64_t> queries{0}, visited_total{0}, visited_max{0}, high_water{0},
      overflows{0}, switches{0};
  phase_progress::begin(samples.samples.size(), "view samples");  // the queries
  run_with_thread_limit(c.parameters.threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::uint64_t count = 0, total = 0, most = 0, deepest = 0, overflowed = 0,
                                      switched = 0;
                        // One stack buffer for every sample of the range.
                        std::vector<std::uint32_t> stack(options.stack_capacity);
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const ViewSample& sample = samples.samples[i];
                          if (!needs_query[i]) continue;  // not regular, or lit: out of reach
                          QueryPoint p;
                          p.position = glm::dvec3(sample.position);
                          p.receiver = sample.receiver;
                          p.light_depth = sample_light_depth(light, p.position);
                          QueryWork work;
                          QueryAnswer answer = QueryAnswer::lit;
                          switch (options.query) {
                            case QueryKind::stack:
                            case QueryKind::depth:
                              answer = query_stack(context, p, stack, work);
                              if (answer == QueryAnswer::stack_overflow) {
                                ++overflowed;
                                answer = query_stackless(context, p, work);
                              }
                              break;
                            case QueryKind::stackless:
                              answer = query_stackless(context, p, work);
                              break;
                            case QueryKind::hybrid:
                              answer = query_hybrid(context, p, stack, work);
                              break;
                          }
                          result.shadowed[i] = answer == QueryAnswer::shadowed ? 1 : 0;
                          result.nodes_visited[i] = std::uint32_t(work.nodes_visited);
                          ++count;
                          total += work.nodes_visited;
                          most = std::max(most, work.nodes_visited);
                          deepest = std::max<std::uint64_t>(deepest, work.stack_high_water);
                          switched += work.hybrid_switches;
                        }
                        // Sums and maxima of integers: the totals do not depend on the
                        // partitioning.
                        phase_progress::advance(range.size());
                        queries += count;
                        visited_total += total;
                        overflows += overflowed;
                        switches += switched;
                        for (std::uint64_t seen = visited_max.load(); seen < most;)
                          visited_max.compare_exchange_weak(seen, most);
                        for (std::uint64_t seen = high_water.load(); seen < deepest;)
                          high_water.compare_exchange_weak(seen, deepest);
                      });
  });
  clock.lap(query_phase);
  result.phase_ms = clock.times();
  PsvQueryTotals totals;
  totals.queries = queries.load();
  totals.nodes_visited_total = visited_total.load();
  totals.nodes_visited_max = visited_max.load();
  totals.stack_high_water = high_water.load();
  totals.stack_overflows = overflows.load();
  totals.hybrid_switches = switches.load();
  result.counters = psv_counters(build, totals, options, build.planes->exact_fallbacks());
  return result;
}

}  // namespace shadowcts::psv
