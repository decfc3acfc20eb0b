// The simd lightassign against the reference at 1920 x 1080 on many_lights and depth_gaps with
// 32 ... 1 M lights (the cases of lightassign_bench: triangles/4 lights), in one run. Every
// iteration's output is checked to be the reference's (lists, bounds, counters): a port that
// differs is an error, not a time.
//   build/bench/lightassign_simd_bench [--benchmark_filter=clustered/many_lights/1048576]
//   build/bench/lightassign_simd_bench --benchmark_filter='/clustered/|brute'  (issue 22's ratios)
// On a shared machine, `taskset -c 0` (one oneTBB thread) makes the CPU column the whole work.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>

#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/lightassign/light_bvh.h"
#include "simd/lightassign/lightassign_algorithm.h"
#include "simd/lightassign/lightassign_kernels.h"
#include "simd/simd_target.h"

namespace shadowcts {
namespace {

struct FullHdCase {
  Case c;
  ViewSamples samples;
  std::unique_ptr<PreparedScene> scene;
  std::map<std::string, AlgorithmOutput> reference;  // per variant, for the check
};

FullHdCase& full_hd_case(const std::string& generator, std::uint64_t lights) {
  static std::map<std::pair<std::string, std::uint64_t>, std::unique_ptr<FullHdCase>> cache;
  auto& entry = cache[{generator, lights}];
  if (!entry) {
    cache.clear();  // one case in memory at a time (1 M lights: 4 M triangles)
    auto& fresh = cache[{generator, lights}];
    fresh = std::make_unique<FullHdCase>();
    // depth_gaps starts at 1k triangles (250 lights).
    fresh->c = make_fixture(generator, generator == "depth_gaps"
                                           ? std::max<std::uint64_t>(4 * lights, 1024)
                                           : 4 * lights);
    fresh->c.camera.width = 1920;
    fresh->c.camera.height = 1080;
    fresh->samples = generate_view_samples(fresh->c);
    fresh->scene = std::make_unique<PreparedScene>(prepare_scene(fresh->c, fresh->samples));
    return *fresh;
  }
  return *entry;
}

bool same_output(const AlgorithmOutput& a, const AlgorithmOutput& b) {
  const LightLists &x = a.light_lists, &y = b.light_lists;
  if (x.offsets != y.offsets || x.lights != y.lights || x.list_of_sample != y.list_of_sample ||
      x.bounds.size() != y.bounds.size() || a.counters != b.counters)
    return false;
  for (std::size_t k = 0; k < x.bounds.size(); ++k)
    if (x.bounds[k].min != y.bounds[k].min || x.bounds[k].max != y.bounds[k].max) return false;
  return true;
}

void BM_LightAssign(benchmark::State& state, const std::string& generator,
                    const std::string& variant, bool simd) {
  static const std::unique_ptr<Algorithm> reference = make_lightassign();
  static const std::unique_ptr<Algorithm> ported = make_simd_lightassign();
  FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  const Algorithm& algorithm = simd ? *ported : *reference;
  AlgorithmOutput output;
  double build_ms = 0.0, query_ms = 0.0;
  for (auto _ : state) {
    output = algorithm.run(*f.scene, variant);
    for (const auto& [phase, ms] : output.phase_ms) (phase == "build" ? build_ms : query_ms) += ms;
  }
  auto known = f.reference.find(variant);
  if (known == f.reference.end())
    known = f.reference.emplace(variant, simd ? reference->run(*f.scene, variant) : output).first;
  if (!same_output(known->second, output)) state.SkipWithError("not the reference's lists");
  state.counters["lights"] = double(f.c.ranged_lights.size());
  for (const auto& [name, value] : output.counters)
    if (name == "list_lengths_total" || name == "unique_clusters")
      state.counters[name] = double(value);
  state.counters["build_ms"] = build_ms / double(state.iterations());
  state.counters["query_ms"] = query_ms / double(state.iterations());
  if (simd) state.SetLabel(simd::dispatched_target_name());
}

// The brute-force baseline of issue 22 ("every light against every cluster", Paper II's tiled
// brute force): the clustered variant's clusters and boxes (from the reference's output, not
// timed), every light tested against every box by the simd leaf test and exact cull, lists built
// as the clustered variants build theirs (oneTBB over the clusters). Timed: the assignment alone
// (the light arrays in Morton order are built before the loop), so the ratio to a whole simd
// clustered run understates the gap. Its lists must be the clustered lists, in the same order.
void BM_Brute(benchmark::State& state, const std::string& generator) {
  static const std::unique_ptr<Algorithm> reference = make_lightassign();
  FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  auto known = f.reference.find("clustered");
  if (known == f.reference.end())
    known = f.reference.emplace("clustered", reference->run(*f.scene, "clustered")).first;
  const LightLists& clustered = known->second.light_lists;
  const simd::LightBvhLanes lights(f.c.ranged_lights);
  LightLists out;
  for (auto _ : state) {
    out = LightLists{};
    build_light_lists(clustered.bounds.size(), out, [&](std::size_t k, auto& list) {
      return simd::test_every_light(lights, clustered.bounds[k], list);
    });
  }
  if (out.offsets != clustered.offsets || out.lights != clustered.lights)
    state.SkipWithError("not the clustered lists");
  state.counters["lights"] = double(f.c.ranged_lights.size());
  state.counters["unique_clusters"] = double(clustered.bounds.size());
  state.counters["pairs"] = double(f.c.ranged_lights.size()) * double(clustered.bounds.size());
  state.SetLabel(simd::dispatched_target_name());
}

// Reference before simd for every (generator, lights, variant): each case is built once.
void register_all() {
  for (const std::string generator : {"many_lights", "depth_gaps"})
    for (const std::int64_t lights : {32, 1024, 32768, 1048576}) {
      for (const std::string variant : {"tiled", "clustered", "clustered+eb", "clustered+en"})
        for (const bool simd : {false, true}) {
          const std::string name =
              std::string(simd ? "simd/" : "reference/") + variant + "/" + generator;
          benchmark::RegisterBenchmark(name.c_str(), BM_LightAssign, generator, variant, simd)
              ->Arg(lights)
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime()
              ->MinTime(0.5);
        }
      benchmark::RegisterBenchmark(("brute/" + generator).c_str(), BM_Brute, generator)
          ->Arg(lights)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->MinTime(0.5);
    }
}

}  // namespace
}  // namespace shadowcts

int main(int argc, char** argv) {
  shadowcts::register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
