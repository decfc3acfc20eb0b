#include "reference/metric/metric_shadows.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <span>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "reference/metric/seeded_random.h"
#include "reference/metric/traversal.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts::metric {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::span<const std::uint32_t> cluster_triangles_of(const Clustering& clustering, std::size_t k) {
  return {clustering.triangles.data() + clustering.cluster_begin[k], clustering.size(k)};
}

// Closed meshes whose bounding box (enlarged by the margin) may hold the point light: the light
// may be inside the solid, where the faces that face it are not the ones a segment leaves by.
std::vector<bool> meshes_around_light(const Case& c, const LightFrame& frame) {
  std::vector<bool> around(c.meshes.size(), false);
  if (frame.directional) return around;
  std::vector<glm::dvec3> lo(c.meshes.size(), glm::dvec3(INFINITY)),
      hi(c.meshes.size(), glm::dvec3(-INFINITY));
  for (const Triangle& t : c.triangles)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo[t.mesh] = glm::min(lo[t.mesh], glm::dvec3(v));
      hi[t.mesh] = glm::max(hi[t.mesh], glm::dvec3(v));
    }
  for (std::size_t m = 0; m < c.meshes.size(); ++m)
    around[m] = glm::all(glm::greaterThanEqual(frame.light_position, lo[m] - frame.margin)) &&
                glm::all(glm::lessThanEqual(frame.light_position, hi[m] + frame.margin));
  return around;
}

}  // namespace

MetricOptions parse_metric_variant(const std::string& variant) {
  MetricOptions options;
  std::string kind = variant;
  const std::size_t digits = variant.find_first_of("0123456789");
  if (digits != std::string::npos) {
    kind = variant.substr(0, digits);
    const std::string number = variant.substr(digits);
    if (number.size() > 4 || number.find_first_not_of("0123456789") != std::string::npos ||
        std::stoul(number) == 0)
      throw std::invalid_argument("metric: bad max_triangles in variant '" + variant + "'");
    options.max_triangles = std::uint32_t(std::stoul(number));
  }
  if (kind == "spheres") {
    options.capsules = false;
  } else if (kind == "median") {
    options.build = TreeBuild::median;
  } else if (kind != "capsules") {
    throw std::invalid_argument("metric: unknown variant '" + variant +
                                "' (capsules, spheres or median, optionally with max_triangles)");
  }
  return options;
}

ClusteredScene cluster_scene(const Case& c, const MetricOptions& options) {
  ClusteringParameters parameters;
  parameters.max_triangles = options.max_triangles;
  parameters.seed = mix_seed(c.parameters.seed, clustering_stream);
  ClusteredScene scene;
  scene.clustering = cluster_triangles(c, parameters);
  const std::vector<int> orientations = closed_mesh_orientations(c);
  const std::size_t count = scene.clustering.cluster_count();
  scene.volumes.resize(count);
  scene.normal_cones.resize(count);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const auto triangles = cluster_triangles_of(scene.clustering, k);
          scene.normal_cones[k] = normal_cone(c, triangles, orientations);
          scene.volumes[k] =
              bound_cluster(c, triangles, options.capsules, scene.normal_cones[k].axis);
        }
      });
  return scene;
}

LightStructure build_light_structure(const Case& c, const ClusteredScene& scene,
                                     const MetricOptions& options) {
  LightStructure structure;
  structure.frame = make_light_frame(c);
  const LightFrame& frame = structure.frame;
  const std::vector<bool> around_light = meshes_around_light(c, frame);
  const glm::dvec3 light = frame.directional ? frame.towards_light : frame.light_position;
  for (std::uint32_t k = 0; k < scene.volumes.size(); ++k) {
    const ClusterVolume& volume = scene.volumes[k];
    if (options.normal_cone_culling && !around_light[scene.clustering.cluster_mesh[k]]) {
      // The bounding sphere of a capsule: around its segment's midpoint.
      const glm::dvec3 centre = 0.5 * (volume.axis_begin + volume.axis_end);
      const double reach =
          volume.radius + frame.margin + 0.5 * glm::length(volume.axis_end - volume.axis_begin);
      if (faces_away_from_light(scene.normal_cones[k], centre, reach, !frame.directional, light)) {
        ++structure.clusters_culled_facing_away;
        continue;
      }
    }
    structure.elements.push_back(make_light_space_element(frame, volume, k));
  }
  const std::uint64_t seed = mix_seed(c.parameters.seed, tree_stream);
  structure.tree = options.build == TreeBuild::median
                       ? build_metric_tree_by_median(frame, structure.elements, seed)
                       : build_metric_tree_by_insertion(frame, structure.elements,
                                                        scene_partition_distance(frame, c), seed);
  return structure;
}

MetricRun run_metric(const Case& c, const ViewSamples& samples, const MetricOptions& options) {
  hard_shadow_light(c);  // throws InputError without a point or directional light
  check_receivers(c, samples);
  MetricRun run;
  run_with_thread_limit(c.parameters.threads, [&] {
    auto start = std::chrono::steady_clock::now();
    const ClusteredScene scene = cluster_scene(c, options);
    run.clustering_seconds = seconds_since(start);

    start = std::chrono::steady_clock::now();
    const LightStructure structure = build_light_structure(c, scene, options);
    run.build_seconds = seconds_since(start);

    start = std::chrono::steady_clock::now();
    TraversalScene traversal;
    traversal.c = &c;
    traversal.light = hard_shadow_light(c);
    traversal.clustering = &scene.clustering;
    traversal.volumes = &scene.volumes;
    traversal.elements = &structure.elements;
    traversal.tree = &structure.tree;
    traversal.frame = structure.frame;
    traversal.ray_length = 4.0 * structure.frame.scale;  // the scene's cube has diagonal 2 sqrt(3)

    run.output.shadowed.assign(samples.samples.size(), 0);
    std::atomic<std::uint64_t> nodes_visited{0}, clusters_without_hit{0}, triangle_tests{0};
    phase_progress::begin(samples.samples.size(), "view samples");
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        TraversalCounters local;
                        std::vector<std::uint32_t> stack;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const ViewSample& sample = samples.samples[i];
                          if (sample.sample_class != SampleClass::regular) continue;
                          run.output.shadowed[i] =
                              sample_is_shadowed(traversal, sample, local, stack) ? 1 : 0;
                        }
                        // Sums of integers: the totals do not depend on the partitioning.
                        nodes_visited += local.nodes_visited;
                        clusters_without_hit += local.clusters_tested_without_hit;
                        triangle_tests += local.triangle_tests;
                        phase_progress::advance(range.size());
                      });
    run.traversal_seconds = seconds_since(start);

    MetricCounters& counters = run.counters;
    counters.clusters = scene.clustering.cluster_count();
    counters.capsules = std::uint64_t(
        std::count_if(scene.volumes.begin(), scene.volumes.end(),
                      [](const ClusterVolume& v) { return v.shape == VolumeShape::capsule; }));
    counters.clusters_culled_facing_away = structure.clusters_culled_facing_away;
    counters.tree_nodes = structure.tree.nodes.size();
    counters.tree_depth = tree_depth(structure.tree);
    counters.traversal.nodes_visited = nodes_visited.load();
    counters.traversal.clusters_tested_without_hit = clusters_without_hit.load();
    counters.traversal.triangle_tests = triangle_tests.load();
  });
  run.output.counters = to_counters(run.counters);
  run.bytes_per_cluster = sizeof(ClusterVolume) + sizeof(NormalCone) + 2 * sizeof(std::uint32_t) +
                          sizeof(LightSpaceElement) + sizeof(MetricTreeNode);
  return run;
}

}  // namespace shadowcts::metric
