// End to end on a large procedural fixture against the fast (Embree) oracle. CI runs 1 M
// triangles; bench/metric_scale_bench runs 1 M and 10 M with timings and memory per cluster.
#include <chrono>
#include <iostream>

#include <gtest/gtest.h>

#include "reference/metric/metric_shadows.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts::metric {
namespace {

void run_end_to_end(std::uint64_t triangles) {
  using clock = std::chrono::steady_clock;
  auto start = clock::now();
  Case c = make_fixture("ground_blockers", triangles);
  c.camera.width = c.camera.height = 256;
  const ViewSamples samples = generate_view_samples(c);
  const double setup_seconds = std::chrono::duration<double>(clock::now() - start).count();
  const MetricRun run = run_metric(c, samples, MetricOptions{});
  start = clock::now();
  const HardShadowTruth truth = embree_hard_shadow_oracle(c, samples);
  const double oracle_seconds = std::chrono::duration<double>(clock::now() - start).count();
  const HardShadowComparison comparison = compare_hard_shadows(run.output.shadowed, truth);
  EXPECT_EQ(comparison.leaks + comparison.false_shadows, 0u) << comparison.reason;
  EXPECT_GT(comparison.robust, comparison.compared / 2);  // the band leaves most samples robust
  const MetricCounters& counters = run.counters;
  EXPECT_GT(counters.clusters, c.triangles.size() / 40);
  std::cout << c.name << ": " << c.triangles.size() << " triangles, " << counters.clusters
            << " clusters (" << counters.capsules << " capsules), clustering "
            << run.clustering_seconds << " s, tree " << run.build_seconds << " s, traversal "
            << run.traversal_seconds << " s, " << run.bytes_per_cluster << " bytes per cluster ("
            << double(run.bytes_per_cluster * counters.clusters) / 1048576.0 << " MiB), "
            << counters.traversal.nodes_visited << " nodes visited, "
            << counters.traversal.triangle_tests << " triangle tests; fixture + samples "
            << setup_seconds << " s, Embree oracle " << oracle_seconds << " s; robust "
            << comparison.robust << ", mismatches " << comparison.leaks + comparison.false_shadows
            << "\n";
}

TEST(MetricScale, OneMillionTrianglesEndToEnd) {
  run_end_to_end(1'000'000);
}

}  // namespace
}  // namespace shadowcts::metric
