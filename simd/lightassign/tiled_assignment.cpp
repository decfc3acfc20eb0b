#include "simd/lightassign/tiled_assignment.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/tiled_assignment.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/phase_clock.h"
#include "simd/lightassign/lightassign_kernels.h"
#include "simd/lightassign/unique_clusters.h"

namespace shadowcts::simd {

AlgorithmOutput assign_lights_tiled(const PreparedScene& scene, std::uint32_t tile_size) {
  PhaseClock clock;
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  const RegularSamples& regular = scene.samples;
  const ViewFrustum frustum(c.camera);
  const std::uint32_t tiles_x = (samples.width + tile_size - 1) / tile_size;
  const std::uint32_t tiles_y = (samples.height + tile_size - 1) / tile_size;
  const std::uint32_t tile_count = tiles_x * tiles_y;
  const std::size_t n = samples.samples.size();

  // One cluster per tile with regular samples (a constant key), the view depth per sample.
  std::vector<double> depth(n, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, regular.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      depth[regular.index[i]] = frustum.depth(glm::dvec3(regular.position(i)));
  });
  UninitializedVector<std::uint32_t> member_regular;
  const std::vector<std::uint32_t> no_key(regular.size(), 0);
  const UniqueClusters tiles = find_unique_clusters(regular, no_key.data(), samples.width,
                                                    samples.height, tile_size, member_regular);
  const std::size_t lists = tiles.keys.size();

  // Per tile: the min/max depth sub-frustum, the declared box, and what its plane test reads.
  std::vector<TileVolume> volumes(lists);
  LightLists out;
  out.bounds.resize(lists);
  std::vector<std::uint32_t> grown(lists, 0);
  std::vector<std::uint32_t> list_of_tile(tile_count, UniqueClusters::no_cluster);
  const double origin_length = glm::length(frustum.origin());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lists, 16), [&](const auto& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const std::uint32_t tile = tiles.tiles[t];
      list_of_tile[tile] = std::uint32_t(t);
      const SubFrustum f =
          tile_sub_frustum(tile, tiles_x, tile_size, samples.width, samples.height, depth.data(),
                           tiles.members.data() + tiles.member_offsets[t],
                           tiles.members.data() + tiles.member_offsets[t + 1]);
      out.bounds[t] = frustum.bounding_box(f);
      grown[t] = grow_to_contain_all(out.bounds[t], regular,
                                     member_regular.data() + tiles.member_offsets[t],
                                     member_regular.data() + tiles.member_offsets[t + 1]);
      // ViewFrustum::sphere_may_meet's planes: along - slope * depth >= 0 with along = x, -x,
      // -y, y.
      TileVolume& v = volumes[t];
      v.near_depth = f.near_depth;
      v.far_depth = f.far_depth;
      v.slope[0] = frustum.slope_x(f.x0);
      v.slope[1] = -frustum.slope_x(f.x1);
      v.slope[2] = -frustum.slope_y(f.y0);
      v.slope[3] = frustum.slope_y(f.y1);
      for (int p = 0; p < 4; ++p) v.norm[p] = std::sqrt(1.0 + v.slope[p] * v.slope[p]);
      v.origin_length = origin_length;
      v.box = out.bounds[t];
    }
  });

  clock.lap(build_phase);

  // Per light: the tiles it covers.
  const std::size_t light_count = c.ranged_lights.size();
  std::vector<TileRect> rects(light_count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, light_count, 4096), [&](const auto& r) {
    for (std::size_t l = r.begin(); l != r.end(); ++l)
      rects[l] = covered_tiles(frustum, c.ranged_lights[l], tile_size, tiles_x, tiles_y);
  });

  // Candidate lists in light order, as the reference's, built over chunks of lights in parallel:
  // each chunk counts per tile, a scan over (tile, chunk) places every chunk's entries, then each
  // chunk writes its own.
  auto for_each_list = [&](const TileRect& rect, auto&& f) {
    for (std::uint32_t y = rect.y0; y <= rect.y1 && rect.x0 <= rect.x1; ++y)
      for (std::uint32_t x = rect.x0; x <= rect.x1; ++x)
        if (const std::uint32_t list = list_of_tile[y * tiles_x + x];
            list != UniqueClusters::no_cluster)
          f(list);
  };
  constexpr std::size_t chunk = 8192;
  const std::size_t chunks = (light_count + chunk - 1) / chunk;
  std::vector<std::uint64_t> place(chunks * lists, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const auto& r) {
    for (std::size_t ch = r.begin(); ch != r.end(); ++ch) {
      std::uint64_t* counts = place.data() + ch * lists;
      for (std::size_t l = ch * chunk; l < std::min(light_count, (ch + 1) * chunk); ++l)
        for_each_list(rects[l], [&](std::uint32_t list) { ++counts[list]; });
    }
  });
  std::vector<std::uint64_t> candidate_offsets(lists + 1, 0);
  for (std::size_t t = 0; t < lists; ++t) {
    std::uint64_t at = candidate_offsets[t];
    for (std::size_t ch = 0; ch < chunks; ++ch) {
      const std::uint64_t count = place[ch * lists + t];
      place[ch * lists + t] = at;
      at += count;
    }
    candidate_offsets[t + 1] = at;
  }
  std::vector<std::uint32_t> candidates(candidate_offsets.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const auto& r) {
    for (std::size_t ch = r.begin(); ch != r.end(); ++ch) {
      std::uint64_t* fill = place.data() + ch * lists;
      for (std::size_t l = ch * chunk; l < std::min(light_count, (ch + 1) * chunk); ++l)
        for_each_list(rects[l],
                      [&](std::uint32_t list) { candidates[fill[list]++] = std::uint32_t(l); });
    }
  });

  // Per tile: the sub-frustum planes, then the exact sphere/box test against the declared box.
  const ViewFrame frame(c.camera);
  const ListWork work = build_light_lists(lists, out, [&](std::size_t t, auto& list) {
    return cull_tile_candidates(c.ranged_lights, frame, volumes[t],
                                candidates.data() + candidate_offsets[t],
                                std::size_t(candidate_offsets[t + 1] - candidate_offsets[t]), list);
  });
  out.list_of_sample = tiles.cluster_of_sample;
  clock.lap(query_phase);

  std::uint64_t grown_total = 0;
  for (const std::uint32_t g : grown) grown_total += g;
  AlgorithmOutput output;
  output.counters =
      light_assignment_counters(out, samples, work, tile_key_bits(tiles_x, tiles_y), grown_total);
  output.light_lists = std::move(out);
  output.phase_ms = clock.times();
  return output;
}

}  // namespace shadowcts::simd
