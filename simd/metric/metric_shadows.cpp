#include "simd/metric/metric_shadows.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <glm/geometric.hpp>

#include "reference/metric/metric_tree.h"
#include "reference/metric/seeded_random.h"
#include "shadowcts/phase_progress.h"
#include "simd/metric/metric_tree.h"
#include "simd/metric/traversal.h"

namespace shadowcts::simd::metric {
namespace {

namespace ref = shadowcts::metric;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The bounding box of every mesh's vertices, and of all of them: the reference reads them in two
// sequential passes over the triangles (meshes_around_light and scene_partition_distance).
struct CasterBoxes {
  std::vector<glm::dvec3> lo, hi;  // per mesh
  glm::dvec3 all_lo{INFINITY}, all_hi{-INFINITY};
};

// Only the box of all vertices where the light is directional (the mesh boxes are read for a point
// light only): per-mesh partial boxes cost a copy of every mesh's box per range of triangles.
CasterBoxes caster_boxes(const PreparedScene& scene, bool per_mesh) {
  if (!per_mesh) {
    using Box = std::pair<glm::dvec3, glm::dvec3>;
    const CasterArrays& t = scene.casters;
    const Box all = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, t.size(), 16384),
        Box(glm::dvec3(INFINITY), glm::dvec3(-INFINITY)),
        [&](const tbb::blocked_range<std::size_t>& range, Box box) {
          for (std::size_t i = range.begin(); i != range.end(); ++i)
            for (int k = 0; k < 3; ++k) {
              const glm::dvec3 v(t.corner(i, k));
              box.first = glm::min(box.first, v);
              box.second = glm::max(box.second, v);
            }
          return box;
        },
        [](const Box& a, const Box& b) {
          return Box(glm::min(a.first, b.first), glm::max(a.second, b.second));
        });
    CasterBoxes out;
    out.all_lo = all.first;
    out.all_hi = all.second;
    return out;
  }
  // Per-mesh boxes, reduced in parallel: min and max do not depend on the order. A body per
  // worker (not a copy of every box per range of triangles).
  struct MeshBoxes {
    const CasterArrays* t;
    std::vector<glm::dvec3> lo, hi;
    MeshBoxes(const CasterArrays& casters, std::size_t meshes)
        : t(&casters), lo(meshes, glm::dvec3(INFINITY)), hi(meshes, glm::dvec3(-INFINITY)) {}
    MeshBoxes(MeshBoxes& other, tbb::split) : MeshBoxes(*other.t, other.lo.size()) {}
    void operator()(const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
        for (int k = 0; k < 3; ++k) {
          const glm::dvec3 v(t->corner(i, k));
          lo[t->mesh[i]] = glm::min(lo[t->mesh[i]], v);
          hi[t->mesh[i]] = glm::max(hi[t->mesh[i]], v);
        }
    }
    void join(const MeshBoxes& other) {
      for (std::size_t m = 0; m < lo.size(); ++m) {
        lo[m] = glm::min(lo[m], other.lo[m]);
        hi[m] = glm::max(hi[m], other.hi[m]);
      }
    }
  };
  const std::size_t meshes = scene.casters.mesh_closed.size();
  MeshBoxes boxes(scene.casters, meshes);
  tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, scene.casters.size(), 16384), boxes);
  CasterBoxes out;
  out.lo = std::move(boxes.lo);
  out.hi = std::move(boxes.hi);
  for (std::size_t m = 0; m < meshes; ++m) {
    out.all_lo = glm::min(out.all_lo, out.lo[m]);
    out.all_hi = glm::max(out.all_hi, out.hi[m]);
  }
  return out;
}

// As the reference's meshes_around_light: closed meshes whose bounding box, enlarged by the
// margin, may hold the point light (then their clusters are never culled by their normals).
std::vector<bool> meshes_around_light(const CasterBoxes& boxes, const ref::LightFrame& frame,
                                      std::size_t meshes) {
  std::vector<bool> around(meshes, false);
  if (frame.directional) return around;
  for (std::size_t m = 0; m < meshes; ++m)
    around[m] = glm::all(glm::greaterThanEqual(frame.light_position, boxes.lo[m] - frame.margin)) &&
                glm::all(glm::lessThanEqual(frame.light_position, boxes.hi[m] + frame.margin));
  return around;
}

}  // namespace

SimdMetricOptions parse_simd_metric_variant(const std::string& variant) {
  SimdMetricOptions options;
  options.metric = ref::parse_metric_variant(variant);
  if (options.metric.build != ref::TreeBuild::insertion)
    throw std::invalid_argument("metric (simd): variant '" + variant +
                                "' uses the median build, which the simd backend does not port");
  return options;
}

ref::LightStructure build_light_structure(const PreparedScene& scene,
                                          const ref::ClusteredScene& clustered,
                                          const ref::MetricOptions& options) {
  const Case& c = scene.source;
  ref::LightStructure structure;
  // The prepared scene's S is Case::scale(), which the reference computes again.
  structure.frame = ref::make_light_frame(c, scene.scale);
  const ref::LightFrame& frame = structure.frame;
  const CasterBoxes boxes = caster_boxes(scene, !frame.directional);
  const std::vector<bool> around_light =
      meshes_around_light(boxes, frame, scene.casters.mesh_closed.size());
  const glm::dvec3 light = frame.directional ? frame.towards_light : frame.light_position;
  const std::size_t count = clustered.volumes.size();
  std::vector<ref::LightSpaceElement> all(count);
  std::vector<std::uint8_t> culled(count, 0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count, 256),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const ref::ClusterVolume& volume = clustered.volumes[k];
          if (options.normal_cone_culling && !around_light[clustered.clustering.cluster_mesh[k]]) {
            const glm::dvec3 centre = 0.5 * (volume.axis_begin + volume.axis_end);
            const double reach = volume.radius + frame.margin +
                                 0.5 * glm::length(volume.axis_end - volume.axis_begin);
            if (ref::faces_away_from_light(clustered.normal_cones[k], centre, reach,
                                           !frame.directional, light)) {
              culled[k] = 1;
              continue;
            }
          }
          all[k] = ref::make_light_space_element(frame, volume, std::uint32_t(k));
        }
      });
  structure.elements.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    if (culled[k])
      ++structure.clusters_culled_facing_away;
    else
      structure.elements.push_back(all[k]);
  }
  const std::uint64_t seed = ref::mix_seed(c.parameters.seed, ref::tree_stream);
  structure.tree = simd::metric::build_metric_tree_by_insertion(
      frame, structure.elements, ref::box_partition_distance(frame, boxes.all_lo, boxes.all_hi),
      seed);
  return structure;
}

SimdMetricRun run_metric(const PreparedScene& scene, const SimdMetricOptions& options) {
  const Case& c = scene.source;
  // Throws InputError without a point or directional light, as the reference does.
  const HardShadowLight light = hard_shadow_light(c);
  SimdMetricRun run;

  auto start = std::chrono::steady_clock::now();
  const ref::ClusteredScene clustered = ref::cluster_scene(c, options.metric);
  const ClusterTriangles triangles = cluster_triangles_soa(scene.casters, clustered.clustering);
  run.clustering_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  double cpu_start = process_cpu_seconds();
  const ref::LightStructure structure = build_light_structure(scene, clustered, options.metric);
  ref::TraversalScene traversal_scene;
  traversal_scene.c = &c;
  traversal_scene.light = light;
  traversal_scene.clustering = &clustered.clustering;
  traversal_scene.volumes = &clustered.volumes;
  traversal_scene.elements = &structure.elements;
  traversal_scene.tree = &structure.tree;
  traversal_scene.frame = structure.frame;
  traversal_scene.ray_length = 4.0 * structure.frame.scale;  // as the reference
  const PacketNodes nodes = packet_nodes(traversal_scene, triangles, options.decision_window);
  run.build_seconds = seconds_since(start);
  run.build_cpu_seconds = process_cpu_seconds() - cpu_start;

  start = std::chrono::steady_clock::now();
  cpu_start = process_cpu_seconds();
  const SampleTiles tiles = sample_tiles(scene.samples, scene.view_samples.width,
                                         options.packet <= 8    ? 8
                                         : options.packet <= 16 ? 16
                                                                : 64);
  PacketTraversal traversal;
  traversal.scene = &traversal_scene;
  traversal.nodes = &nodes;
  traversal.triangles = &triangles;
  traversal.prepared = &scene;
  traversal.tiles = &tiles;
  // Written by the traversal per view sample (0 for the others): no serial scatter afterwards.
  run.output.shadowed.assign(scene.view_samples.samples.size(), 0);
  std::uint8_t* const shadowed = run.output.shadowed.data();
  std::atomic<std::uint64_t> nodes_visited{0}, clusters_without_hit{0}, triangle_tests{0};
  phase_progress::begin(tiles.size(), "sample tiles");
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      ref::TraversalCounters local;
                      traverse_tiles(traversal, range.begin(), range.end(), shadowed, local);
                      // Sums of integers: the totals do not depend on the partitioning.
                      nodes_visited += local.nodes_visited;
                      clusters_without_hit += local.clusters_tested_without_hit;
                      triangle_tests += local.triangle_tests;
                      phase_progress::advance(range.size());
                    });
  run.traversal_seconds = seconds_since(start);
  run.traversal_cpu_seconds = process_cpu_seconds() - cpu_start;

  ref::MetricCounters& counters = run.counters;
  counters.clusters = clustered.clustering.cluster_count();
  counters.capsules = std::uint64_t(std::count_if(
      clustered.volumes.begin(), clustered.volumes.end(),
      [](const ref::ClusterVolume& v) { return v.shape == ref::VolumeShape::capsule; }));
  counters.clusters_culled_facing_away = structure.clusters_culled_facing_away;
  counters.tree_nodes = structure.tree.nodes.size();
  counters.tree_depth = ref::tree_depth(structure.tree);
  counters.traversal.nodes_visited = nodes_visited.load();
  counters.traversal.clusters_tested_without_hit = clusters_without_hit.load();
  counters.traversal.triangle_tests = triangle_tests.load();
  run.output.counters = ref::to_counters(counters);
  return run;
}

}  // namespace shadowcts::simd::metric
