#include "simd/psv/psv_shadows.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "reference/closed_mesh_culling.h"
#include "reference/psv/rule_culling.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "simd/psv/query_packet.h"

namespace shadowcts::simd::psv {
namespace {

// Bound on every coordinate the plane tests see (the reference's): triangles, light, samples.
double coordinate_bound(const PreparedScene& scene) {
  // The samples' largest coordinate in float (converting to double is exact and keeps the order),
  // a loop the compiler vectorizes; the case's scale is the prepared scene's copy.
  const RegularSamples& s = scene.samples;
  float largest = 0.0f;
  for (const std::vector<float>* axis : {&s.px, &s.py, &s.pz})
    for (const float x : *axis) largest = std::max(largest, std::fabs(x));
  return std::max({scene.scale, double(largest), 1e-30});
}

}  // namespace

SimdPsvBuild build_psv(const PreparedScene& scene, std::uint64_t seed) {
  const Case& c = scene.source;
  SimdPsvBuild result;
  ref::PsvBuild& build = result.build;
  build.light = hard_shadow_light(c);
  check_receivers(c, scene.samples);
  build.planes =
      std::make_unique<ref::PlaneSide>(build.light, c.triangles, coordinate_bound(scene));
  const PlaneSide planes(*build.planes);
  // The culling tests read the prepared samples: a twentieth of the view samples' bytes.
  const std::vector<bool> face_culling = ref::culling_clear_of_segment_starts(
      c, scene.samples, build.light, meshes_safe_for_face_culling(c, scene.samples));
  const RegularSamples& s = scene.samples;
  run_with_thread_limit(c.parameters.threads, [&] {
    const CasterReach reach(build.light, s.px, s.py, s.pz);
    const std::vector<std::uint32_t> order = psv::insertion_order(
        c, scene.casters.casts, *build.planes, face_culling, reach, seed, build.statistics);
    build.reached = reach.samples_reached(c.triangles, order, s.px, s.py, s.pz, s.receiver);
    build.statistics.samples_out_of_reach =
        std::uint64_t(std::count(build.reached.begin(), build.reached.end(), std::uint8_t(0)));
    build.tree =
        psv::build_top_tree(c, planes, order, build.statistics, result.corners, result.work);
  });
  build.planes->count_exact_fallbacks(planes.exact_tests());
  return result;
}

SimdPsvResult psv_hard_shadows(const PreparedScene& scene, const SimdPsvOptions& options) {
  PhaseClock clock;
  const SimdPsvBuild built = build_psv(scene, options.psv.seed);
  const ref::PsvBuild& build = built.build;
  const bool depth_test = options.psv.query != ref::QueryKind::stack;
  const ref::QueryContext exact(build.tree, *build.planes, depth_test);
  const PlaneSide planes(*build.planes);
  const QueryTree q{build.tree, built.corners, planes, exact, depth_test, build.light.directional};
  clock.lap(build_phase);

  const RegularSamples& samples = scene.samples;
  std::vector<std::uint8_t> shadowed(samples.size(), 0);
  std::vector<std::uint32_t> visited(samples.size(), 0);
  const std::uint32_t packet = std::clamp<std::uint32_t>(options.packet, 1, max_packet);
  const Packets packets = tile_packets(samples, build.reached, scene.source.camera.width, packet);
  tbb::combinable<ref::PsvQueryTotals> partial;
  phase_progress::begin(packets.sample.size(), "regular samples");  // the queries
  run_with_thread_limit(scene.source.parameters.threads, [&] {
    // Whole packets per range: a packet never depends on the partitioning.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, packets.begin.size() - 1, 8),
        [&](const tbb::blocked_range<std::size_t>& range) {
          query_packets(q, options.psv, build.light, samples, packets, range.begin(), range.end(),
                        shadowed.data(), visited.data(), partial.local());
          phase_progress::advance(packets.begin[range.end()] - packets.begin[range.begin()]);
        });
  });
  clock.lap(query_phase);
  build.planes->count_exact_fallbacks(planes.exact_tests());

  // Sums and maxima of integers: the totals do not depend on the partitioning.
  ref::PsvQueryTotals totals;
  partial.combine_each([&](const ref::PsvQueryTotals& t) {
    totals.queries += t.queries;
    totals.nodes_visited_total += t.nodes_visited_total;
    totals.nodes_visited_max = std::max(totals.nodes_visited_max, t.nodes_visited_max);
    totals.stack_high_water = std::max(totals.stack_high_water, t.stack_high_water);
    totals.stack_overflows += t.stack_overflows;
    totals.hybrid_switches += t.hybrid_switches;
  });
  SimdPsvResult result;
  result.shadowed = scene.per_view_sample(shadowed, std::uint8_t(0));
  result.nodes_visited = scene.per_view_sample(visited, std::uint32_t(0));
  result.counters = ref::psv_counters(build, totals, options.psv, build.planes->exact_fallbacks());
  result.phase_ms = clock.times();
  result.build_work = built.work;
  return result;
}

}  // namespace shadowcts::simd::psv
