// Light assignment at 1920 x 1080 on many_lights with 32 ... 1 M lights: the exact oracle and
// every lightassign variant (Paper II's Table 2 shape: tiled against clustered time), with the
// papers' efficiency metric as counters. A variant that is not complete and sound is an error.
//   build/bench/lightassign_bench [--benchmark_filter=.../1048576]
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "oracles/light_assignment/light_assignment_comparison.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/light_assignment_oracle.h"

namespace shadowcts {
namespace {

struct FullHdCase {
  Case c;
  ViewSamples samples;
  LightAssignmentTruth plain, normals;
};

// many_lights places triangles/4 lights (capped at 1 M).
const FullHdCase& full_hd_case(std::uint64_t lights) {
  static std::map<std::uint64_t, std::unique_ptr<FullHdCase>> cache;
  auto& entry = cache[lights];
  if (!entry) {
    entry = std::make_unique<FullHdCase>();
    entry->c = make_fixture("many_lights", 4 * lights);
    entry->c.camera.width = 1920;
    entry->c.camera.height = 1080;
    entry->samples = generate_view_samples(entry->c);
    entry->plain = exact_light_assignment_oracle(entry->c, entry->samples, false);
    entry->normals = exact_light_assignment_oracle(entry->c, entry->samples, true);
  }
  return *entry;
}

void BM_LightAssignmentOracle(benchmark::State& state) {
  const FullHdCase& f = full_hd_case(std::uint64_t(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(exact_light_assignment_oracle(f.c, f.samples, false).lights.data());
  state.counters["lights"] = double(f.c.ranged_lights.size());
  state.counters["exact_minimum"] = double(f.plain.exact_minimum());
}

void BM_LightAssign(benchmark::State& state, const std::string& variant) {
  static const std::unique_ptr<Algorithm> algorithm = make_lightassign();
  const FullHdCase& f = full_hd_case(std::uint64_t(state.range(0)));
  AlgorithmOutput output;
  for (auto _ : state) output = algorithm->run(f.c, f.samples, variant);
  const LightAssignmentComparison cmp =
      compare_light_lists(output.light_lists, f.c, f.samples,
                          light_lists_use_normal_rule(variant) ? f.normals : f.plain);
  if (cmp.verdict != Verdict::pass) state.SkipWithError(cmp.reason.c_str());
  state.counters["lights"] = double(f.c.ranged_lights.size());
  state.counters["lighting_ratio"] = cmp.lighting_ratio;
}

void light_counts(benchmark::internal::Benchmark* b) {
  for (const std::int64_t lights : {32, 1024, 32768, 1048576}) b->Arg(lights);
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_LightAssignmentOracle)->Apply(light_counts)->Iterations(1);
BENCHMARK_CAPTURE(BM_LightAssign, tiled, std::string("tiled"))->Apply(light_counts);
BENCHMARK_CAPTURE(BM_LightAssign, clustered, std::string("clustered"))->Apply(light_counts);
BENCHMARK_CAPTURE(BM_LightAssign, clustered_eb, std::string("clustered+eb"))->Apply(light_counts);

}  // namespace
}  // namespace shadowcts

BENCHMARK_MAIN();
