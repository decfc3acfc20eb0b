#pragma once
// The simd `metric` pipeline for one prepared scene (Deves et al. 2018, section 3), the same
// steps as reference/metric/metric_shadows.h: the reference's clustering and bounding volumes
// (the per-model precomputation, timed on its own), then per light the light-space elements and
// the tree built in parallel (identical to the reference's), and the packet traversal.
#include <cstdint>

#include "reference/metric/metric_shadows.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd::metric {

struct SimdMetricOptions {
  shadowcts::metric::MetricOptions metric;  // insertion build only
  // Samples per packet: 8 (4 x 2 pixels), 16 (4 x 4) or 64 (8 x 8). The widest walks each node
  // for the most lanes at once: its per-visit work (the node's loads, branches and stack entry)
  // is shared by the most samples.
  std::uint32_t packet = 64;
  double decision_window = 0x1p-40;  // PacketNodes::decision_window
};

// The variants the port implements: "capsules", "spheres" and "capsules16" (and the reference's
// names with another max_triangles); throws std::invalid_argument for the median build.
SimdMetricOptions parse_simd_metric_variant(const std::string& variant);

// What the reference's build_light_structure computes, from the same clustered scene: the
// elements of the clusters that do not face away from the light, in cluster order, and the tree.
shadowcts::metric::LightStructure build_light_structure(
    const PreparedScene& scene, const shadowcts::metric::ClusteredScene& clustered,
    const shadowcts::metric::MetricOptions& options);

struct SimdMetricRun {
  AlgorithmOutput output;  // per view sample; counters as the reference's, plus light on caster
  shadowcts::metric::MetricCounters counters;
  double clustering_seconds = 0.0;  // clustering, bounding volumes, triangles in cluster order
  double build_seconds = 0.0;       // elements, tree, node records
  double traversal_seconds = 0.0;
  // CPU time of all the process's threads during the traversal: on a shared machine a steadier
  // measure of the work than the wall clock (benchmarks only).
  double traversal_cpu_seconds = 0.0;
  double build_cpu_seconds = 0.0;
};

// On the threads of the caller's oneTBB arena; deterministic for the case's seed and any thread
// count or Highway target. Needs a point or directional light.
SimdMetricRun run_metric(const PreparedScene& scene, const SimdMetricOptions& options);

}  // namespace shadowcts::simd::metric
