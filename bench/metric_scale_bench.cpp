// metric end to end on ground_blockers at 1 M and 10 M triangles (256 x 256 samples) against the
// fast oracle, the reference and the simd port with the same options: clustering, tree build and
// traversal time (the reference's also memory per cluster). A robust mismatch is an error.
//   build/bench/metric_scale_bench
#include <benchmark/benchmark.h>

#include "reference/metric/metric_shadows.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/prepared_scene.h"
#include "simd/metric/metric_shadows.h"

namespace shadowcts {
namespace {

Case scale_case(const benchmark::State& state) {
  Case c = make_fixture("ground_blockers", std::uint64_t(state.range(0)));
  c.camera.width = c.camera.height = 256;
  return c;
}

// The run's answers against the fast oracle, and its times.
template <class Run>
void report(benchmark::State& state, const Case& c, const ViewSamples& samples, const Run& run) {
  const HardShadowComparison comparison =
      compare_hard_shadows(run.output.shadowed, embree_hard_shadow_oracle(c, samples));
  if (comparison.leaks + comparison.false_shadows != 0)
    state.SkipWithError(comparison.reason.c_str());
  state.counters["triangles"] = double(c.triangles.size());
  state.counters["clusters"] = double(run.counters.clusters);
  state.counters["clustering_s"] = run.clustering_seconds;
  state.counters["build_s"] = run.build_seconds;
  state.counters["traversal_s"] = run.traversal_seconds;
}

void BM_MetricEndToEnd(benchmark::State& state) {
  const Case c = scale_case(state);
  const ViewSamples samples = generate_view_samples(c);
  metric::MetricRun run;
  for (auto _ : state) run = metric::run_metric(c, samples, metric::MetricOptions{});
  report(state, c, samples, run);
  state.counters["bytes_per_cluster"] = double(run.bytes_per_cluster);
}

void BM_MetricSimdEndToEnd(benchmark::State& state) {
  const Case c = scale_case(state);
  const ViewSamples samples = generate_view_samples(c);
  const PreparedScene scene = prepare_scene(c, samples);
  simd::metric::SimdMetricOptions options;
  options.metric = metric::MetricOptions{};
  simd::metric::SimdMetricRun run;
  for (auto _ : state) run = simd::metric::run_metric(scene, options);
  report(state, c, samples, run);
}

BENCHMARK(BM_MetricEndToEnd)
    ->Arg(1'000'000)
    ->Arg(10'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_MetricSimdEndToEnd)
    ->Arg(1'000'000)
    ->Arg(10'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace shadowcts

BENCHMARK_MAIN();
