#include "gpu/metric/metric_shadows.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/metric/metric_tree.h"
#include "reference/metric/traversal.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts::gpu_metric {
namespace {

namespace ref = shadowcts::metric;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

PivotKind pivot_kind(const ref::LightFrame& frame, const ref::LightSpaceElement& e) {
  if (e.covers_everything) return PivotKind::covers_everything;
  if (frame.directional)
    return e.centre == ref::CentreKind::point ? PivotKind::disk : PivotKind::capsule_2d;
  return e.centre == ref::CentreKind::point ? PivotKind::point_cone : PivotKind::arc_cone;
}

}  // namespace

GpuMetricOptions parse_gpu_metric_variant(const std::string& variant) {
  GpuMetricOptions options;
  options.metric = ref::parse_metric_variant(variant);
  if (options.metric.build != ref::TreeBuild::insertion)
    throw std::invalid_argument("metric (cuda): variant '" + variant +
                                "' uses the median build, which the cuda backends do not port");
  return options;
}

MetricInput metric_kernel_input(const PreparedScene& scene, const ref::ClusteredScene& clustered,
                                const ref::LightStructure& structure, double decision_window) {
  const Case& c = scene.source;
  const ref::LightFrame& frame = structure.frame;
  const HardShadowLight light = hard_shadow_light(c);
  MetricInput input;
  MetricFrame& f = input.frame;
  f.directional = frame.directional;
  f.light_position = frame.light_position;
  f.towards_light = frame.towards_light;
  f.plane_x = frame.plane_x;
  f.plane_y = frame.plane_y;
  f.ray_length = 4.0 * frame.scale;  // as the reference's run_metric
  f.light_float = frame.directional ? c.light->direction : c.light->position;
  f.light_exact = frame.directional ? light.direction : light.position;
  f.angle_window = decision_window;
  f.length_window = decision_window * frame.scale;

  // The thresholds by the reference's own expressions (for_each_candidate_element), so that the
  // kernel compares with the same doubles.
  input.nodes.reserve(structure.tree.nodes.size());
  for (const ref::MetricTreeNode& node : structure.tree.nodes) {
    const ref::LightSpaceElement& e = structure.elements[node.pivot];
    MetricNode n;
    n.light_distance = node.light_distance;
    n.pivot_light_distance = e.light_distance;
    n.a = e.a;
    n.b = e.b;
    n.arc_normal = e.arc.normal;
    n.radius = e.radius;
    n.overlap_low = node.overlap_min - frame.slack;
    n.overlap_high = node.overlap_max + frame.slack;
    n.far_side = node.partition_distance - frame.slack;
    n.near_side = node.partition_distance + frame.slack;
    for (int k = 0; k < 3; ++k) n.child[k] = node.child[k];
    n.pivot = node.pivot;
    n.cluster = e.cluster;
    n.kind = pivot_kind(frame, e);
    input.nodes.push_back(n);
  }

  const ref::Clustering& clustering = clustered.clustering;
  input.clusters.reserve(clustering.cluster_count());
  for (std::size_t k = 0; k < clustering.cluster_count(); ++k) {
    const ref::ClusterVolume& volume = clustered.volumes[k];
    // As the reference's segment_meets_slabs.
    input.clusters.push_back({volume.slab_normal, volume.slab_min - frame.margin,
                              volume.slab_max + frame.margin, clustering.cluster_begin[k],
                              clustering.cluster_begin[k + 1]});
  }
  input.triangles.reserve(clustering.triangles.size());
  for (std::uint32_t t : clustering.triangles) {
    const Triangle& triangle = c.triangles[t];
    input.triangles.push_back({triangle.v0, triangle.v1, triangle.v2, t});
  }

  const RegularSamples& samples = scene.samples;
  input.sample_positions.reserve(samples.size());
  input.sample_receivers = samples.receiver;
  input.sample_receiver_triangles.reserve(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    input.sample_positions.push_back(samples.position(i));
    MetricReceiver receiver;
    if (samples.receiver[i] != no_receiver) {
      const Triangle& r = c.triangles[samples.receiver[i]];
      receiver = {r.v0, r.v1, r.v2, 1};
    }
    input.sample_receiver_triangles.push_back(receiver);
  }
  return input;
}

GpuMetricRun run_metric(const PreparedScene& scene, const GpuMetricOptions& options,
                        KernelRunner run_kernel) {
  const Case& c = scene.source;
  // Throws InputError without a point or directional light, as the reference does.
  const HardShadowLight light = hard_shadow_light(c);
  check_receivers(c, scene.view_samples);
  GpuMetricRun run;
  // The emulator spreads blocks over oneTBB and the host's parts run on it: all keep to the
  // case's thread limit, as the reference does.
  run_with_thread_limit(c.parameters.threads, [&] {
    auto start = std::chrono::steady_clock::now();
    const ref::ClusteredScene clustered = ref::cluster_scene(c, options.metric);
    run.clustering_seconds = seconds_since(start);

    // The tree is built on the host by the reference and uploaded: it has one node per cluster
    // that faces the light (tens of thousands at 1M triangles, against millions of samples), and
    // the paper's insertion build is sequential by nature (each element's path depends on the
    // pivots inserted before it).
    start = std::chrono::steady_clock::now();
    const ref::LightStructure structure = ref::build_light_structure(c, clustered, options.metric);
    MetricInput input = metric_kernel_input(scene, clustered, structure, options.decision_window);
    input.stack_limit = options.stack_limit;
    run.build_seconds = seconds_since(start);

    start = std::chrono::steady_clock::now();
    // The kernel frees each staging array once it has its own copy (on the device, or in the
    // emulator's memory), so no phase holds two copies of the samples.
    const double ray_length = input.frame.ray_length;
    const MetricResult result = run_kernel(std::move(input));
    std::vector<std::uint8_t> shadowed(scene.samples.size(), 0);
    std::vector<std::uint32_t> handed_back;
    for (std::size_t i = 0; i < result.state.size(); ++i) {
      const std::uint8_t state = result.state[i];
      shadowed[i] = state == sample_shadowed ? 1 : 0;
      if (state == sample_unsure) ++run.near_threshold_samples;
      if (state == sample_stack_overflow) ++run.stack_overflow_samples;
      if (state == sample_exact_test) ++run.exact_test_samples;
      if (handed_to_host(state)) handed_back.push_back(std::uint32_t(i));
    }
    // The samples handed back, walked by the reference's own code with its counters.
    ref::TraversalScene traversal;
    traversal.c = &c;
    traversal.light = light;
    traversal.clustering = &clustered.clustering;
    traversal.volumes = &clustered.volumes;
    traversal.elements = &structure.elements;
    traversal.tree = &structure.tree;
    traversal.frame = structure.frame;
    traversal.ray_length = ray_length;
    std::atomic<std::uint64_t> nodes_visited{0}, clusters_without_hit{0}, triangle_tests{0};
    if (!handed_back.empty())
      phase_progress::begin(handed_back.size(), "samples", "the host's traversal");
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, handed_back.size(), 16),
        [&](const tbb::blocked_range<std::size_t>& range) {
          ref::TraversalCounters local;
          std::vector<std::uint32_t> stack;
          for (std::size_t u = range.begin(); u != range.end(); ++u) {
            const std::uint32_t i = handed_back[u];
            const ViewSample& sample = scene.view_samples.samples[scene.samples.index[i]];
            shadowed[i] = ref::sample_is_shadowed(traversal, sample, local, stack) ? 1 : 0;
          }
          // Sums of integers: the totals do not depend on the partitioning.
          nodes_visited += local.nodes_visited;
          clusters_without_hit += local.clusters_tested_without_hit;
          triangle_tests += local.triangle_tests;
          phase_progress::advance(range.size());
        });
    run.output.shadowed = scene.per_view_sample(shadowed, std::uint8_t(0));
    run.traversal_seconds = seconds_since(start);

    ref::MetricCounters& counters = run.counters;
    counters.clusters = clustered.clustering.cluster_count();
    counters.capsules = std::uint64_t(std::count_if(
        clustered.volumes.begin(), clustered.volumes.end(),
        [](const ref::ClusterVolume& v) { return v.shape == ref::VolumeShape::capsule; }));
    counters.clusters_culled_facing_away = structure.clusters_culled_facing_away;
    counters.tree_nodes = structure.tree.nodes.size();
    counters.tree_depth = ref::tree_depth(structure.tree);
    counters.traversal.nodes_visited = result.nodes_visited + nodes_visited.load();
    counters.traversal.clusters_tested_without_hit =
        result.clusters_tested_without_hit + clusters_without_hit.load();
    counters.traversal.triangle_tests = result.triangle_tests + triangle_tests.load();
  });
  const std::uint64_t blocks = (scene.samples.size() + threads_per_block - 1) / threads_per_block;
  run.kernel_threads = blocks * threads_per_block;
  run.output.counters = ref::to_counters(run.counters);
  run.output.counters.push_back({"near_threshold_samples", run.near_threshold_samples});
  run.output.counters.push_back({"stack_overflow_samples", run.stack_overflow_samples});
  run.output.counters.push_back({"exact_test_samples", run.exact_test_samples});
  return run;
}

}  // namespace shadowcts::gpu_metric
