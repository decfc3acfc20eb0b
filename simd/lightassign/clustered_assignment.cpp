#include "simd/lightassign/clustered_assignment.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

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

  // Keys, unique clusters and their members' boxes in one pass over the samples per band
  // (cluster_samples). The slices depend on the deepest sample only through their count (the
  // last slice takes what lies beyond): the pass runs with the slices to the far plane, and again
  // only where the deepest sample lies past the far plane's last slice. Beside them, the
  // reference's light BVH, built in parallel and in lanes: each of the two leaves a core idle at
  // times (at 1 M lights, 18.9-19.7 against 18.0-18.7 ms a call on many_lights). Its arrays come
  // from oneTBB's allocator, which serves any thread the blocks freed by the last call.
  const ViewFrame frame(c.camera);
  const ClusterGrid to_far(c.camera, settings.tile_size, settings.normal_divisions, 0.0);
  SampleClusters sampled;
  std::optional<ClusterGrid> deepest_grid;
  std::optional<LightBvhLanes> bvh;
  tbb::parallel_invoke(
      [&] {
        sampled = cluster_samples(regular, frame, to_far, samples.width, samples.height);
        deepest_grid.emplace(c.camera, settings.tile_size, settings.normal_divisions,
                             sampled.deepest);
        if (auto why = deepest_grid->overflow_reason())
          throw std::invalid_argument("lightassign: " + *why);
        if (deepest_grid->slices() != to_far.slices())
          sampled = cluster_samples(regular, frame, *deepest_grid, samples.width, samples.height);
      },
      [&] { bvh.emplace(c.ranged_lights); });
  const ClusterGrid& grid = *deepest_grid;
  const LightBvhLanes& lanes = *bvh;
  UniqueClusters& clusters = sampled.clusters;
  const std::size_t lists = clusters.keys.size();

  // Bounds and cones per cluster (Sections 3.2, 4.2), as the reference's, from the members' boxes
  // and, where a variant reads them one by one, the members' positions and normals as arrays. An
  // implicit box grows (in member order) only where it does not hold its members' box.
  UninitializedVector<std::uint32_t> member_regular;
  auto members_of = [&](std::size_t k) {
    return std::pair(member_regular.data() + clusters.member_offsets[k],
                     member_regular.data() + clusters.member_offsets[k + 1]);
  };
  if (settings.explicit_normal_cones)
    member_regular =
        cluster_members(clusters, regular, samples.width, samples.height, settings.tile_size);
  LightLists out;
  out.bounds.resize(lists);
  std::vector<NormalCone> cones(lists);
  const bool use_cones = settings.explicit_normal_cones || settings.normal_divisions > 0;
  std::vector<std::uint8_t> outgrown(lists, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lists, 16), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const ClusterCoordinates coordinates = grid.unpack(clusters.keys[k]);
      Aabb& box = out.bounds[k];
      if (settings.explicit_bounds) {
        // grow_to_contain from the first member's position: the members' box.
        box.min = sampled.low[k];
        box.max = sampled.high[k];
      } else {
        box = frustum.bounding_box(grid.sub_frustum(coordinates));
        outgrown[k] = !box_holds(box, sampled.low[k], sampled.high[k]);
      }
      if (settings.explicit_normal_cones) {
        const auto [first, last] = members_of(k);
        ExplicitNormalCone accumulate;
        for (const std::uint32_t* m = first; m < last; ++m)
          accumulate.add_direction(regular.normal(*m));
        cones[k] = accumulate.axis_only();
        for (const std::uint32_t* m = first; m < last; ++m)
          ExplicitNormalCone::widen(cones[k], regular.normal(*m));
      } else if (settings.normal_divisions > 0) {
        cones[k] = normal_cell_cone(coordinates.normal, settings.normal_divisions);
      }
    }
  });
  std::vector<std::uint32_t> grown(lists, 0);
  if (std::find(outgrown.begin(), outgrown.end(), 1) != outgrown.end()) {
    if (member_regular.empty())
      member_regular =
          cluster_members(clusters, regular, samples.width, samples.height, settings.tile_size);
    tbb::parallel_for(std::size_t(0), lists, [&](std::size_t k) {
      if (!outgrown[k]) return;
      const auto [first, last] = members_of(k);
      grown[k] =
          grow_to_contain_all(out.bounds[k], sampled.low[k], sampled.high[k], regular, first, last);
    });
  }

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
  out.list_of_sample = std::move(clusters.cluster_of_sample);
  clock.lap(query_phase);

  // Every regular sample is in one cluster: the lighting computations are the clusters' member
  // counts times their list lengths.
  std::uint64_t grown_total = 0, lighting = 0;
  for (std::size_t k = 0; k < lists; ++k) {
    grown_total += grown[k];
    lighting += std::uint64_t(clusters.member_offsets[k + 1] - clusters.member_offsets[k]) *
                (out.offsets[k + 1] - out.offsets[k]);
  }
  AlgorithmOutput output;
  output.counters =
      light_assignment_counters(out, lighting, work, std::uint64_t(grid.bits()), grown_total);
  output.light_lists = std::move(out);
  output.phase_ms = clock.times();
  return output;
}

}  // namespace shadowcts::simd
