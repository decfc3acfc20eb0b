#include "simd/lightassign/clustered_assignment.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/light_bvh.h"
#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/normal_cone.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/phase_clock.h"
#include "simd/lightassign/light_bvh.h"
#include "simd/lightassign/lightassign_kernels.h"
#include "simd/lightassign/unique_clusters.h"

namespace shadowcts::simd {

AlgorithmOutput assign_lights_clustered(const PreparedScene& scene,
                                        const ClusteredSettings& settings) {
  PhaseClock clock;
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  const RegularSamples& regular = scene.samples;
  const ViewFrustum frustum(c.camera);
  const std::size_t n = samples.samples.size();

  // View depths of the regular samples; the slices reach the deepest (max is exact in any order).
  std::vector<double> depth(regular.size());
  const double deepest = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, regular.size(), 4096), 0.0,
      [&](const auto& r, double d) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          depth[i] = frustum.depth(glm::dvec3(regular.position(i)));
          d = std::max(d, depth[i]);
        }
        return d;
      },
      [](double a, double b) { return std::max(a, b); });
  const ClusterGrid grid(c.camera, settings.tile_size, settings.normal_divisions, deepest);
  if (auto why = grid.overflow_reason()) throw std::invalid_argument("lightassign: " + *why);

  // Cluster keys (Section 3.1), per pixel; the slices in lanes, per block of samples.
  std::vector<std::uint32_t> slice(regular.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, regular.size(), 4096), [&](const auto& r) {
    slices_of(grid, depth.data() + r.begin(), r.size(), slice.data() + r.begin());
  });
  std::vector<std::uint32_t> pixel_key(n, 0);
  std::vector<std::uint8_t> clustered(n, 0);
  const std::uint32_t width = samples.width;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, regular.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const std::uint32_t s = regular.index[i];
      ClusterCoordinates key;
      key.i = (s % width) / settings.tile_size;
      key.j = (s / width) / settings.tile_size;
      key.k = slice[i];
      if (settings.normal_divisions > 0)
        key.normal = quantize_normal(regular.normal(i), settings.normal_divisions);
      pixel_key[s] = grid.pack(key);
      clustered[s] = 1;
    }
  });
  const UniqueClusters clusters =
      find_unique_clusters(pixel_key, clustered, width, samples.height, settings.tile_size);
  const std::size_t lists = clusters.keys.size();

  // Bounds and cones per cluster (Sections 3.2, 4.2), as the reference's.
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
        box.min = box.max = samples.samples[clusters.members[first]].position;
        for (std::uint32_t m = first + 1; m < last; ++m)
          grow_to_contain(box, samples.samples[clusters.members[m]].position);
      } else {
        box = frustum.bounding_box(grid.sub_frustum(key));
        grown[k] = grow_to_contain_all(box, samples, clusters.members.data() + first,
                                       clusters.members.data() + last);
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

  // The reference's light BVH, built in parallel and in lanes.
  const LightBvhLanes lanes(c.ranged_lights);
  clock.lap(build_phase);

  // Per cluster: traversal and the exact sphere/box cull in lanes, then the back-face rule on the
  // lights that met the box (in order, as the reference applies it after the box test).
  const ListWork work = build_light_lists(lists, out, [&](std::size_t k, auto& list) {
    const std::size_t before = list.size();
    ListWork w = query_light_bvh(lanes, out.bounds[k], list);
    if (use_cones) {
      std::size_t kept = before;
      for (std::size_t e = before; e < list.size(); ++e) {
        const std::uint32_t index = list[e];
        if (light_behind_cone(cones[k], out.bounds[k], glm::dvec3(c.ranged_lights[index].centre)))
          ++w.backface_culled;
        else
          list[kept++] = index;
      }
      list.resize(kept);
    }
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

}  // namespace shadowcts::simd
