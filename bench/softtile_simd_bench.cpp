// The simd softtile against the reference and the Embree ray-sampling baseline (build + query) at
// 1920 x 1080 on foliage at 100 k and 1 M triangles (the reference at 100 k only: at 1 M it takes
// about 5 minutes on one thread; the runner times it, docs/soft-shadow-speed.md), in one run, one
// timed iteration each (minutes per run). Each simd output is checked to be the reference's
// (answers and counters): a port that differs is an error, not a time.
//   build/bench/softtile_simd_bench [--benchmark_filter=foliage/100000]
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <string>

#include "reference/embree/soft_shadow_embree.h"
#include "reference/softtile/softtile_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/simd_target.h"
#include "simd/softtile/softtile_algorithm.h"

namespace shadowcts {
namespace {

struct FullHdCase {
  Case c;
  ViewSamples samples;
  std::unique_ptr<PreparedScene> scene;
  std::string checked_variant;  // the reference output kept for the simd check
  AlgorithmOutput reference;
};

FullHdCase& full_hd_case(std::uint64_t triangles) {
  static std::uint64_t key = 0;
  static std::unique_ptr<FullHdCase> entry;
  if (!entry || key != triangles) {
    entry.reset();  // one case in memory at a time
    key = triangles;
    entry = std::make_unique<FullHdCase>();
    entry->c = make_fixture("foliage", triangles);
    entry->c.camera.width = 1920;
    entry->c.camera.height = 1080;
    // One thread: the CPU column is then the whole work, which the shared two-core machines
    // measure far more steadily than wall time.
    entry->c.parameters.threads = 1;
    entry->samples = generate_view_samples(entry->c);
    entry->scene = std::make_unique<PreparedScene>(prepare_scene(entry->c, entry->samples));
  }
  return *entry;
}

void run_timed(benchmark::State& state, const Algorithm& algorithm, const std::string& variant,
               AlgorithmOutput& output) {
  FullHdCase& f = full_hd_case(std::uint64_t(state.range(0)));
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    output = algorithm.run(*f.scene, variant);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  for (const auto& [name, ms] : output.phase_ms) state.counters[name + "_ms"] = ms;
  // The work behind the time: candidates per tile, tests and rasterized triangles per pixel.
  for (const auto& [name, value] : output.counters)
    if (name == "tile_candidates_total" || name == "pixel_triangle_tests" ||
        name == "triangles_rasterized")
      state.counters[name] = double(value);
  state.SetLabel(algorithm.info().backend + " " + variant);
}

void BM_SofttileReference(benchmark::State& state, const std::string& variant) {
  FullHdCase& f = full_hd_case(std::uint64_t(state.range(0)));
  run_timed(state, *make_softtile(), variant, f.reference);
  f.checked_variant = variant;
}

void BM_SofttileSimd(benchmark::State& state, const std::string& variant) {
  FullHdCase& f = full_hd_case(std::uint64_t(state.range(0)));
  AlgorithmOutput output;
  run_timed(state, *make_simd_softtile(), variant, output);
  state.SetLabel("simd " + variant + " (" + simd::dispatched_target_name() + ")");
  if (f.checked_variant == variant && (output.visible_fraction != f.reference.visible_fraction ||
                                       output.counters != f.reference.counters))
    state.SkipWithError("simd output differs from the reference");
}

void BM_EmbreeSoft(benchmark::State& state, const std::string& variant) {
  AlgorithmOutput output;
  run_timed(state, *make_embree_soft_shadow(), variant, output);
}

// Reference, then simd (checked against it), then the Embree baselines, per size.
void sizes(benchmark::internal::Benchmark* b) {
  b->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
}
BENCHMARK_CAPTURE(BM_SofttileReference, grid16, std::string("grid16"))
    ->Apply(sizes)
    ->Arg(100000)
    ->Name("foliage/100000/softtile_reference_grid16");
BENCHMARK_CAPTURE(BM_SofttileSimd, grid16, std::string("grid16"))
    ->Apply(sizes)
    ->Arg(100000)
    ->Name("foliage/100000/softtile_simd_grid16");
BENCHMARK_CAPTURE(BM_EmbreeSoft, rays64, std::string("rays64"))
    ->Apply(sizes)
    ->Arg(100000)
    ->Name("foliage/100000/embree_soft_rays64");
BENCHMARK_CAPTURE(BM_SofttileSimd, grid16, std::string("grid16"))
    ->Apply(sizes)
    ->Arg(1000000)
    ->Name("foliage/1000000/softtile_simd_grid16");
BENCHMARK_CAPTURE(BM_EmbreeSoft, rays64, std::string("rays64"))
    ->Apply(sizes)
    ->Arg(1000000)
    ->Name("foliage/1000000/embree_soft_rays64");

}  // namespace
}  // namespace shadowcts

BENCHMARK_MAIN();
