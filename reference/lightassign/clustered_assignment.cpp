#include "reference/lightassign/clustered_assignment.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/light_bvh.h"
#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/normal_cone.h"
#include "reference/lightassign/unique_clusters.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/geometry/sphere_box.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {

AlgorithmOutput assign_lights_clustered(const Case& c, const ViewSamples& samples,
                                        const ClusteredSettings& settings) {
  PhaseClock clock;
  const ViewFrustum frustum(c.camera);
  const std::size_t n = samples.samples.size();

  // View depths; the slices reach the deepest sample (rounding can put it past the far plane).
  std::vector<double> depth(n, 0.0);
  double deepest = 0.0;
  for (std::size_t s = 0; s < n; ++s)
    if (samples.samples[s].sample_class == SampleClass::regular) {
      depth[s] = frustum.depth(glm::dvec3(samples.samples[s].position));
      deepest = std::max(deepest, depth[s]);
    }
  const ClusterGrid grid(c.camera, settings.tile_size, settings.normal_divisions, deepest);
  if (auto why = grid.overflow_reason()) throw std::invalid_argument("lightassign: " + *why);

  // Cluster keys (Section 3.1).
  std::vector<std::uint32_t> sample_tile(n, UniqueClusters::no_cluster), sample_key(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const ViewSample& sample = samples.samples[s];
      if (sample.sample_class != SampleClass::regular) continue;
      ClusterCoordinates key;
      key.i = sample.pixel_x / settings.tile_size;
      key.j = sample.pixel_y / settings.tile_size;
      key.k = grid.slice_of(depth[s]);
      if (settings.normal_divisions > 0)
        key.normal = quantize_normal(sample.normal, settings.normal_divisions);
      sample_tile[s] = key.j * grid.tiles_x() + key.i;
      sample_key[s] = grid.pack(key);
    }
  });
  const UniqueClusters clusters =
      find_unique_clusters(sample_tile, sample_key, grid.tiles_x() * grid.tiles_y());
  const std::size_t lists = clusters.keys.size();

  // Bounds and cones per cluster (Sections 3.2, 4.2).
  LightLists out;
  out.bounds.resize(lists);
  std::vector<NormalCone> cones(lists);
  const bool use_cones = settings.explicit_normal_cones || settings.normal_divisions > 0;
  std::vector<std::uint32_t> grown(lists, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lists, 16), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::uint32_t first = clusters.member_offsets[k], last = clusters.member_offsets[k + 1];
      const ClusterCoordinates key = grid.unpack(clusters.keys[k]);
      Aabb& box = out.bounds[k];
      if (settings.explicit_bounds) {
        // Min-max reduction over the samples: exact, the box of the float positions.
        box.min = box.max = samples.samples[clusters.members[first]].position;
        for (std::uint32_t m = first + 1; m < last; ++m)
          grow_to_contain(box, samples.samples[clusters.members[m]].position);
      } else {
        box = frustum.bounding_box(grid.sub_frustum(key));
        for (std::uint32_t m = first; m < last; ++m)
          grown[k] += grow_to_contain(box, samples.samples[clusters.members[m]].position);
      }
      if (settings.explicit_normal_cones) {
        ExplicitNormalCone accumulate;
        for (std::uint32_t m = first; m < last; ++m)
          accumulate.add_direction(samples.samples[clusters.members[m]].normal);
        cones[k] = accumulate.axis_only();
        for (std::uint32_t m = first; m < last; ++m)
          ExplicitNormalCone::widen(cones[k], samples.samples[clusters.members[m]].normal);
      } else if (settings.normal_divisions > 0) {
        cones[k] = normal_cell_cone(key.normal, settings.normal_divisions);
      }
    }
  });

  // Light assignment: the BVH per cluster, exact sphere/box at the leaves, then the back-face
  // rule (Section 3.3).
  const LightBvh bvh(c.ranged_lights);
  clock.lap(build_phase);
  const ListWork work = build_light_lists(lists, out, [&](std::size_t k, auto& list) {
    ListWork w;
    w.nodes_tested = bvh.traverse(out.bounds[k], [&](std::uint32_t index) {
      const RangedLight& light = c.ranged_lights[index];
      ++w.light_tests;
      if (!geometry::sphere_meets_box(light.centre, light.range, out.bounds[k].min,
                                      out.bounds[k].max))
        return;
      if (use_cones && light_behind_cone(cones[k], out.bounds[k], glm::dvec3(light.centre))) {
        ++w.backface_culled;
        return;
      }
      list.push_back(index);
    });
    return w;
  });
  out.list_of_sample = clusters.cluster_of_sample;
  clock.lap(query_phase);

  std::uint64_t grown_total = 0;
  for (const std::uint32_t g : grown) grown_total += g;
  AlgorithmOutput output;
  output.counters =
      light_assignment_counters(out, samples, work, std::uint64_t(grid.bits()), grown_total);
  output.light_lists = std::move(out);
  output.phase_ms = clock.times();
  return output;
}

}  // namespace shadowcts
