// ptsv at 1920 x 1080, simd against reference, per variant and fixture (gate_house,
// ground_blockers, closed_shapes at 100k and 1M triangles): the whole run() on one prepared
// scene, with its build and query phases and the test-and-set count as counters. The simd mask
// and counters must be the reference's (checked once per case; an error otherwise).
//   build/bench/ptsv_simd_bench [--benchmark_filter=gate_house/100000]
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "reference/ptsv/ptsv_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/ptsv/ptsv_algorithm.h"

namespace shadowcts {
namespace {

struct FullHdCase {
  Case c;
  ViewSamples samples;
  std::unique_ptr<PreparedScene> scene;
};

const FullHdCase& full_hd_case(const std::string& generator, std::uint64_t triangles) {
  static std::map<std::pair<std::string, std::uint64_t>, std::unique_ptr<FullHdCase>> cache;
  auto& entry = cache[{generator, triangles}];
  if (!entry) {
    entry = std::make_unique<FullHdCase>();
    entry->c = make_fixture(generator, triangles);
    entry->c.camera.width = 1920;
    entry->c.camera.height = 1080;
    entry->samples = generate_view_samples(entry->c);
    entry->scene = std::make_unique<PreparedScene>(prepare_scene(entry->c, entry->samples));
  }
  return *entry;
}

void BM_Ptsv(benchmark::State& state, const std::string& generator, const std::string& backend,
             const std::string& variant) {
  static const std::unique_ptr<Algorithm> reference = make_ptsv();
  static const std::unique_ptr<Algorithm> port = make_simd_ptsv();
  const FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  const Algorithm& algorithm = backend == "simd" ? *port : *reference;
  AlgorithmOutput output;
  double build_ms = 0.0, query_ms = 0.0;
  for (auto _ : state) {
    output = algorithm.run(*f.scene, variant);
    build_ms += output.phase_ms[0].second;
    query_ms += output.phase_ms[1].second;
  }
  if (backend == "simd") {
    const AlgorithmOutput expected = reference->run(*f.scene, variant);
    if (expected.shadowed != output.shadowed || expected.counters != output.counters)
      state.SkipWithError("simd output differs from the reference's");
  }
  state.counters["build_ms"] = build_ms / double(state.iterations());
  state.counters["query_ms"] = query_ms / double(state.iterations());
  for (const auto& [name, value] : output.counters)
    if (name == "test_and_set_operations") state.counters["test_and_set"] = double(value);
}

void register_all() {
  for (const std::string generator : {"gate_house", "ground_blockers", "closed_shapes"})
    for (const std::string backend : {"reference", "simd"})
      for (const std::string variant : {"twopass", "explicit+planes", "implicit"})
        benchmark::RegisterBenchmark(
            ("ptsv/" + backend + "/" + variant + "/" + generator).c_str(),
            [=](benchmark::State& s) { BM_Ptsv(s, generator, backend, variant); })
            ->Arg(100000)
            ->Arg(1000000)
            ->Unit(benchmark::kMillisecond)
            ->MeasureProcessCPUTime()  // the oneTBB workers' time too: steadier on a shared machine
            ->Iterations(1);
}

}  // namespace
}  // namespace shadowcts

int main(int argc, char** argv) {
  shadowcts::register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
