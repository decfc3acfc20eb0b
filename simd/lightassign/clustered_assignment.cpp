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

  // The view depths of the regular samples and their depth slices, in lanes per block. The
  // slices depend on the deepest sample only through their count (the last slice takes what lies
  // beyond): they are found in the same pass with the slices to the far plane, and found again
  // only where the deepest sample lies past the far plane's last slice.
  const ViewFrame frame(c.camera);
  constexpr std::size_t block = 4096;
  const std::size_t blocks = (regular.size() + block - 1) / block;
  auto block_size = [&](std::size_t b) {
    return std::min(regular.size(), (b + 1) * block) - b * block;
  };
  UninitializedVector<std::uint32_t> key(regular.size());  // the slice, then the key
  auto find_slices = [&](const ClusterGrid& slicing) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, blocks, 1), 0.0,
        [&](const auto& r, double deepest) {
          double depth[block];
          for (std::size_t b = r.begin(); b != r.end(); ++b) {
            const std::size_t first = b * block, count = block_size(b);
            view_depths(frame, regular.px.data() + first, regular.py.data() + first,
                        regular.pz.data() + first, count, depth);
            for (std::size_t i = 0; i < count; ++i) deepest = std::max(deepest, depth[i]);
            slices_of(slicing, depth, count, key.data() + first);
          }
          return deepest;
        },
        [](double a, double b) { return std::max(a, b); });  // exact in any order
  };
  const ClusterGrid to_far(c.camera, settings.tile_size, settings.normal_divisions, 0.0);
  const double deepest = find_slices(to_far);
  const ClusterGrid grid(c.camera, settings.tile_size, settings.normal_divisions, deepest);
  if (auto why = grid.overflow_reason()) throw std::invalid_argument("lightassign: " + *why);
  if (grid.slices() != to_far.slices()) find_slices(grid);

  // Cluster keys (Section 3.1) per regular sample, row by row (a row's samples are consecutive).
  // The fields take disjoint bits, so a key is its tile's key (pack with k = normal = 0) or'ed
  // with the slice and normal fields packed alone.
  const std::uint32_t width = samples.width;
  const std::vector<std::uint32_t> row_start = regular_rows(regular, width, samples.height);
  std::vector<std::uint32_t> column_of(width);
  for (std::uint32_t x = 0; x < width; ++x) column_of[x] = x / settings.tile_size;
  const int slice_shift = grid.bits_normal();
  tbb::parallel_for(std::uint32_t(0), samples.height, [&](std::uint32_t y) {
    std::vector<std::uint32_t> tile_key(grid.tiles_x());
    for (std::uint32_t i = 0; i < grid.tiles_x(); ++i)
      tile_key[i] = grid.pack({.i = i, .j = y / settings.tile_size, .k = 0, .normal = 0});
    for (std::size_t i = row_start[y]; i < row_start[y + 1]; ++i) {
      std::uint32_t k = tile_key[column_of[regular.index[i] - y * width]] | key[i] << slice_shift;
      if (settings.normal_divisions > 0)
        k |= quantize_normal(regular.normal(i), settings.normal_divisions);
      key[i] = k;
    }
  });
  UninitializedVector<std::uint32_t> member_regular;  // read instead of clusters.members
  UniqueClusters clusters = find_unique_clusters(regular, key.data(), width, samples.height,
                                                 settings.tile_size, member_regular, false);
  const std::size_t lists = clusters.keys.size();

  // Bounds and cones per cluster (Sections 3.2, 4.2), as the reference's, from the members'
  // positions and normals as arrays.
  LightLists out;
  out.bounds.resize(lists);
  std::vector<NormalCone> cones(lists);
  const bool use_cones = settings.explicit_normal_cones || settings.normal_divisions > 0;
  std::vector<std::uint32_t> grown(lists, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lists, 16), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::uint32_t* first = member_regular.data() + clusters.member_offsets[k];
      const std::uint32_t* last = member_regular.data() + clusters.member_offsets[k + 1];
      const ClusterCoordinates coordinates = grid.unpack(clusters.keys[k]);
      Aabb& box = out.bounds[k];
      if (settings.explicit_bounds) {
        box.min = box.max = regular.position(*first);
        for (const std::uint32_t* m = first + 1; m < last; ++m)
          grow_to_contain(box, regular.position(*m));
      } else {
        box = frustum.bounding_box(grid.sub_frustum(coordinates));
        grown[k] = grow_to_contain_all(box, regular, first, last);
      }
      if (settings.explicit_normal_cones) {
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

  // The reference's light BVH, built in parallel and in lanes. (Built beside the clusters in a
  // task group it was slower: its arrays then come from a worker thread's malloc arena, fresh
  // pages on every call.)
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
