// psv at 1920 x 1080: the simd port against the reference and against the Embree peer (build +
// query, the baseline a user would pick), per fixture (gate_house, ground_blockers,
// closed_shapes, foliage at 100k and 1M triangles) and variant: the whole run() on one prepared
// scene, its build and query phases as counters. The simd mask and counters must be the
// reference's (exact_plane_tests aside: each port counts its own); checked once per case. And the
// simd query by packet size (psv_packet/<samples per packet>/...).
//   build/bench/psv_simd_bench [--benchmark_filter=gate_house/1000000]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>

#include "reference/embree/hard_shadow_embree.h"
#include "reference/psv/psv_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/psv/psv_algorithm.h"
#include "simd/psv/psv_shadows.h"

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
    // Hard shadows of a sun disk's centre, as the runner hands it to hard-shadow algorithms.
    if (entry->c.light && entry->c.light->kind == ShadowLightKind::sun_disk)
      entry->c.light->kind = ShadowLightKind::directional;
    entry->samples = generate_view_samples(entry->c);
    entry->scene = std::make_unique<PreparedScene>(prepare_scene(entry->c, entry->samples));
  }
  return *entry;
}

Counters without_exact_plane_tests(Counters counters) {
  std::erase_if(counters, [](const auto& counter) { return counter.first == "exact_plane_tests"; });
  return counters;
}

void BM_Psv(benchmark::State& state, const std::string& generator, const std::string& backend,
            const std::string& variant) {
  static const std::unique_ptr<Algorithm> reference = make_psv();
  static const std::unique_ptr<Algorithm> port = make_simd_psv();
  static const std::unique_ptr<Algorithm> embree = make_embree_hard_shadow();
  const FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  const Algorithm& algorithm =
      backend == "simd" ? *port : (backend == "embree" ? *embree : *reference);
  AlgorithmOutput output;
  double build_ms = 0.0, query_ms = 0.0;
  for (auto _ : state) {
    output = algorithm.run(*f.scene, variant);
    build_ms += output.phase_ms[0].second;
    query_ms += output.phase_ms[1].second;
  }
  if (backend == "simd") {
    const AlgorithmOutput expected = reference->run(*f.scene, variant);
    if (expected.shadowed != output.shadowed ||
        without_exact_plane_tests(expected.counters) != without_exact_plane_tests(output.counters))
      state.SkipWithError("simd output differs from the reference's");
  }
  state.counters["build_ms"] = build_ms / double(state.iterations());
  state.counters["query_ms"] = query_ms / double(state.iterations());
}

// The simd query with `packet` samples per packet (issue 19: packets of 8 or 16 samples, or one
// sample at a time), D-Stackless: each packet size's query phase on the same scene; its mask and
// per-sample node visits are checked against the default packet's.
void BM_PsvPacket(benchmark::State& state, const std::string& generator, std::uint32_t packet) {
  const FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  simd::psv::SimdPsvOptions options;
  options.psv = psv::psv_variant_options("stackless");
  options.psv.seed = f.c.parameters.seed;
  options.packet = packet;
  simd::psv::SimdPsvResult result;
  double query_ms = 0.0;
  for (auto _ : state) {
    result = simd::psv::psv_hard_shadows(*f.scene, options);
    query_ms += result.phase_ms[1].second;
  }
  simd::psv::SimdPsvOptions default_options = options;
  default_options.packet = simd::psv::SimdPsvOptions().packet;
  const simd::psv::SimdPsvResult expected = simd::psv::psv_hard_shadows(*f.scene, default_options);
  if (result.shadowed != expected.shadowed || result.nodes_visited != expected.nodes_visited)
    state.SkipWithError("the mask or the nodes visited depend on the packet size");
  state.counters["query_ms"] = query_ms / double(state.iterations());
}

void register_all() {
  for (const std::string generator :
       {"gate_house", "ground_blockers", "closed_shapes", "foliage"}) {
    const auto add = [&](const std::string& backend, const std::string& variant) {
      benchmark::RegisterBenchmark(
          ("psv/" + backend + "/" + variant + "/" + generator).c_str(),
          [=](benchmark::State& s) { BM_Psv(s, generator, backend, variant); })
          ->Arg(100000)
          ->Arg(1000000)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    };
    add("embree", "robust");
    for (const std::string backend : {"reference", "simd"})
      for (const std::string variant : {"stackless", "depth", "hybrid", "stack32"})
        add(backend, variant);
    for (const std::uint32_t packet : {1u, 4u, 8u, 16u})
      benchmark::RegisterBenchmark(
          ("psv_packet/" + std::to_string(packet) + "/" + generator).c_str(),
          [=](benchmark::State& s) { BM_PsvPacket(s, generator, packet); })
          ->Arg(100000)
          ->Arg(1000000)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(3);
  }
}

}  // namespace
}  // namespace shadowcts

int main(int argc, char** argv) {
  shadowcts::register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
