// The simd metric against the reference and Embree (build + query) at 1920 x 1080 on
// gate_house, ground_blockers and closed_shapes at 1 M triangles, and ground_blockers at 10 M
// (simd and Embree only: the reference takes minutes there), in one run. Each simd output is
// checked to be the reference's (answers and counters) where the reference runs: a port that
// differs is an error, not a time. Times are the phases the algorithms time themselves.
//   build/bench/metric_simd_bench [--benchmark_filter=gate_house/1000000]
#include <benchmark/benchmark.h>

#include <atomic>
#include <ctime>
#include <memory>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/embree/hard_shadow_embree.h"
#include "reference/metric/metric_algorithm.h"
#include "reference/metric/traversal.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/metric/metric_algorithm.h"
#include "simd/metric/metric_shadows.h"
#include "simd/metric/traversal.h"
#include "simd/simd_target.h"

namespace shadowcts {
namespace {

struct FullHdCase {
  Case c;
  ViewSamples samples;
  std::unique_ptr<PreparedScene> scene;
};

FullHdCase& full_hd_case(const std::string& generator, std::uint64_t triangles) {
  static std::pair<std::string, std::uint64_t> key;
  static std::unique_ptr<FullHdCase> entry;
  if (!entry || key != std::pair(generator, triangles)) {
    entry.reset();  // one case in memory at a time
    key = {generator, triangles};
    entry = std::make_unique<FullHdCase>();
    entry->c = make_fixture(generator, triangles);
    entry->c.camera.width = 1920;
    entry->c.camera.height = 1080;
    entry->samples = generate_view_samples(entry->c);
    entry->scene = std::make_unique<PreparedScene>(prepare_scene(entry->c, entry->samples));
  }
  return *entry;
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// CPU seconds of the reference's traversal (its sample_is_shadowed over every regular sample,
// on oneTBB as run_metric runs it): on a shared machine the wall clock of either side depends on
// the other jobs, the CPU time much less.
double reference_query_cpu_seconds(const FullHdCase& f, const std::string& variant) {
  const metric::MetricOptions options = metric::parse_metric_variant(variant);
  const metric::ClusteredScene scene = metric::cluster_scene(f.c, options);
  const metric::LightStructure structure = metric::build_light_structure(f.c, scene, options);
  metric::TraversalScene traversal;
  traversal.c = &f.c;
  traversal.light = hard_shadow_light(f.c);
  traversal.clustering = &scene.clustering;
  traversal.volumes = &scene.volumes;
  traversal.elements = &structure.elements;
  traversal.tree = &structure.tree;
  traversal.frame = structure.frame;
  traversal.ray_length = 4.0 * structure.frame.scale;
  std::atomic<std::uint64_t> shadowed{0};
  const double start = process_cpu_seconds();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.samples.samples.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      metric::TraversalCounters counters;
                      std::vector<std::uint32_t> stack;
                      std::uint64_t local = 0;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const ViewSample& sample = f.samples.samples[i];
                        if (sample.sample_class != SampleClass::regular) continue;
                        local += metric::sample_is_shadowed(traversal, sample, counters, stack);
                      }
                      shadowed += local;
                    });
  return process_cpu_seconds() - start;
}

double phase(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [phase_name, ms] : output.phase_ms)
    if (phase_name == name) return ms;
  return 0.0;
}

void BM_MetricSimd(benchmark::State& state, const std::string& generator,
                   const std::string& variant, std::uint32_t packet, bool with_reference) {
  FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  simd::metric::SimdMetricOptions options = simd::metric::parse_simd_metric_variant(variant);
  options.packet = packet;
  simd::metric::SimdMetricRun run;
  double clustering = 0, build = 0, query = 0, build_cpu = 0, query_cpu = 0;
  for (auto _ : state) {
    run = simd::metric::run_metric(*f.scene, options);
    clustering += run.clustering_seconds;
    build += run.build_seconds;
    query += run.traversal_seconds;
    build_cpu += run.build_cpu_seconds;
    query_cpu += run.traversal_cpu_seconds;
  }
  const double n = double(state.iterations());
  state.counters["simd_clustering_ms"] = 1e3 * clustering / n;
  state.counters["simd_build_ms"] = 1e3 * build / n;
  state.counters["simd_query_ms"] = 1e3 * query / n;
  state.counters["simd_build_cpu_ms"] = 1e3 * build_cpu / n;
  state.counters["simd_query_cpu_ms"] = 1e3 * query_cpu / n;
  const AlgorithmOutput embree = make_embree_hard_shadow()->run(*f.scene, "robust");
  state.counters["embree_build_ms"] = phase(embree, "build");
  state.counters["embree_query_ms"] = phase(embree, "query");
  state.counters["simd_vs_embree_build_query"] =
      (phase(embree, "build") + phase(embree, "query")) / (1e3 * (build + query) / n);
  if (with_reference) {
    const metric::MetricRun reference =
        metric::run_metric(f.c, f.samples, metric::parse_metric_variant(variant));
    if (reference.output.shadowed != run.output.shadowed ||
        reference.output.counters != run.output.counters)
      state.SkipWithError("the simd answers or counters differ from the reference's");
    state.counters["reference_clustering_ms"] = 1e3 * reference.clustering_seconds;
    state.counters["reference_build_ms"] = 1e3 * reference.build_seconds;
    state.counters["reference_query_ms"] = 1e3 * reference.traversal_seconds;
    state.counters["query_speedup"] = reference.traversal_seconds / (query / n);
    state.counters["build_speedup"] = reference.build_seconds / (build / n);
    const double reference_cpu = reference_query_cpu_seconds(f, variant);
    state.counters["reference_query_cpu_ms"] = 1e3 * reference_cpu;
    state.counters["query_cpu_speedup"] = reference_cpu / (query_cpu / n);
  }
  state.SetLabel(simd::dispatched_target_name() + ", packet " + std::to_string(packet));
}

// The simd traversal alone, on one thread, over every tile (the build done once outside the
// timed loop): the steadiest measure of the query's work on a shared machine, and what a profile
// of the query should run.
void BM_MetricSimdQueryOnly(benchmark::State& state, const std::string& generator) {
  FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  const PreparedScene& scene = *f.scene;
  const simd::metric::SimdMetricOptions options =
      simd::metric::parse_simd_metric_variant("capsules16");
  const metric::ClusteredScene clustered = metric::cluster_scene(f.c, options.metric);
  const simd::metric::ClusterTriangles triangles =
      simd::metric::cluster_triangles_soa(scene.casters, clustered.clustering);
  const metric::LightStructure structure =
      simd::metric::build_light_structure(scene, clustered, options.metric);
  metric::TraversalScene traversal_scene;
  traversal_scene.c = &f.c;
  traversal_scene.light = hard_shadow_light(f.c);
  traversal_scene.clustering = &clustered.clustering;
  traversal_scene.volumes = &clustered.volumes;
  traversal_scene.elements = &structure.elements;
  traversal_scene.tree = &structure.tree;
  traversal_scene.frame = structure.frame;
  traversal_scene.ray_length = 4.0 * structure.frame.scale;
  const simd::metric::PacketNodes nodes = simd::metric::packet_nodes(traversal_scene, triangles);
  const simd::metric::SampleTiles tiles =
      simd::metric::sample_tiles(scene.samples, scene.view_samples.width, options.packet);
  simd::metric::PacketTraversal traversal;
  traversal.scene = &traversal_scene;
  traversal.nodes = &nodes;
  traversal.triangles = &triangles;
  traversal.prepared = &scene;
  traversal.tiles = &tiles;
  std::vector<std::uint8_t> shadowed(scene.view_samples.samples.size(), 0);
  metric::TraversalCounters counters;
  for (auto _ : state) {
    counters = {};
    simd::metric::traverse_tiles(traversal, 0, tiles.size(), shadowed.data(), counters);
  }
  state.counters["nodes_visited"] = double(counters.nodes_visited);
  state.counters["triangle_tests"] = double(counters.triangle_tests);
  state.SetLabel(simd::dispatched_target_name() + ", one thread");
}

// The per-frame build alone (elements, tree, node records), against the reference's
// build_light_structure on the same clustered scene, in CPU seconds of the process.
void BM_MetricSimdBuildOnly(benchmark::State& state, const std::string& generator) {
  FullHdCase& f = full_hd_case(generator, std::uint64_t(state.range(0)));
  const PreparedScene& scene = *f.scene;
  const simd::metric::SimdMetricOptions options =
      simd::metric::parse_simd_metric_variant("capsules16");
  const metric::ClusteredScene clustered = metric::cluster_scene(f.c, options.metric);
  const simd::metric::ClusterTriangles triangles =
      simd::metric::cluster_triangles_soa(scene.casters, clustered.clustering);
  double structure_cpu = 0, nodes_cpu = 0, reference_cpu = 0;
  for (auto _ : state) {
    double start = process_cpu_seconds();
    const metric::LightStructure structure =
        simd::metric::build_light_structure(scene, clustered, options.metric);
    structure_cpu += process_cpu_seconds() - start;
    metric::TraversalScene traversal_scene;
    traversal_scene.c = &f.c;
    traversal_scene.clustering = &clustered.clustering;
    traversal_scene.volumes = &clustered.volumes;
    traversal_scene.elements = &structure.elements;
    traversal_scene.tree = &structure.tree;
    traversal_scene.frame = structure.frame;
    start = process_cpu_seconds();
    const simd::metric::PacketNodes nodes = simd::metric::packet_nodes(traversal_scene, triangles);
    nodes_cpu += process_cpu_seconds() - start;
    benchmark::DoNotOptimize(nodes.fast.data());
    start = process_cpu_seconds();
    const metric::LightStructure expected =
        metric::build_light_structure(f.c, clustered, options.metric);
    reference_cpu += process_cpu_seconds() - start;
    benchmark::DoNotOptimize(expected.tree.nodes.data());
  }
  const double n = double(state.iterations());
  state.counters["simd_structure_cpu_ms"] = 1e3 * structure_cpu / n;
  state.counters["simd_nodes_cpu_ms"] = 1e3 * nodes_cpu / n;
  state.counters["reference_build_cpu_ms"] = 1e3 * reference_cpu / n;
}

void register_benchmarks() {
  for (const char* generator : {"gate_house", "ground_blockers", "closed_shapes"})
    benchmark::RegisterBenchmark(
        (std::string("metric_simd_build/") + generator).c_str(),
        [=](benchmark::State& state) { BM_MetricSimdBuildOnly(state, generator); })
        ->Arg(1'000'000)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3);
  for (const char* generator : {"gate_house", "ground_blockers", "closed_shapes"})
    benchmark::RegisterBenchmark(
        (std::string("metric_simd_query/") + generator).c_str(),
        [=](benchmark::State& state) { BM_MetricSimdQueryOnly(state, generator); })
        ->Arg(1'000'000)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(5);
  for (const char* generator : {"gate_house", "ground_blockers", "closed_shapes"})
    for (const char* variant : {"capsules16", "capsules"})
      for (std::uint32_t packet : {64u, 16u, 8u})
        benchmark::RegisterBenchmark((std::string("metric_simd/") + generator + "/" + variant +
                                      "/packet" + std::to_string(packet))
                                         .c_str(),
                                     [=](benchmark::State& state) {
                                       BM_MetricSimd(state, generator, variant, packet, true);
                                     })
            ->Arg(1'000'000)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime()
            ->Iterations(3);
  // The simd port alone (and Embree), for profiles and packet-size comparisons.
  for (const char* generator : {"gate_house", "ground_blockers", "closed_shapes"})
    for (std::uint32_t packet : {64u, 16u, 8u})
      benchmark::RegisterBenchmark((std::string("metric_simd_only/") + generator +
                                    "/capsules16/packet" + std::to_string(packet))
                                       .c_str(),
                                   [=](benchmark::State& state) {
                                     BM_MetricSimd(state, generator, "capsules16", packet, false);
                                   })
          ->Arg(1'000'000)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->Iterations(5);
  benchmark::RegisterBenchmark("metric_simd_only/ground_blockers/capsules16/packet64",
                               [](benchmark::State& state) {
                                 BM_MetricSimd(state, "ground_blockers", "capsules16", 64, false);
                               })
      ->Arg(10'000'000)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
}

}  // namespace
}  // namespace shadowcts

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  shadowcts::register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
