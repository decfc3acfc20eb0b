#include "reference/lightassign/tiled_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/lightassign/light_list_builder.h"
#include "reference/lightassign/unique_clusters.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/geometry/sphere_box.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {
// The tiles that the screen-space bounding rectangle of a light's sphere covers (Paper I,
// Section 6.1): the tangent planes x = s z through the eye bound its projection while the sphere
// lies in front of the eye plane; a sphere reaching the eye plane covers the whole screen.
TileRect covered_tiles(const ViewFrustum& frustum, const RangedLight& light,
                       std::uint32_t tile_size, std::uint32_t tiles_x, std::uint32_t tiles_y) {
  const glm::dvec3 v = frustum.to_view(glm::dvec3(light.centre));
  const double r = light.range;
  TileRect rect;
  if (v.z + r <= 0.0) return rect;  // wholly behind the eye: no sample can be in it
  double px0 = -1.0, px1 = frustum.width() + 1.0, py0 = -1.0, py1 = frustum.height() + 1.0;
  // A relative 2^-30 of depth keeps the tangent formula away from its singularity.
  if (v.z - r > 0x1p-30 * (std::fabs(v.z) + r)) {
    const double denominator = v.z * v.z - r * r;
    auto slopes = [&](double along, double& low, double& high) {
      const double root = r * std::sqrt(std::max(0.0, along * along + denominator));
      low = (along * v.z - root) / denominator;
      high = (along * v.z + root) / denominator;
    };
    double sx0, sx1, sy0, sy1;
    slopes(v.x, sx0, sx1);
    slopes(v.y, sy0, sy1);
    // A thousandth of a pixel and a relative 2^-30 cover the rounding of the slopes.
    const double margin_x = 1e-3 + 0x1p-30 * frustum.width();
    const double margin_y = 1e-3 + 0x1p-30 * frustum.height();
    px0 = frustum.pixel_x(sx0) - margin_x;
    px1 = frustum.pixel_x(sx1) + margin_x;
    py0 = frustum.pixel_y(sy1) - margin_y;  // y grows downwards: the larger slope is on top
    py1 = frustum.pixel_y(sy0) + margin_y;
  }
  if (px1 < 0.0 || py1 < 0.0 || px0 > frustum.width() || py0 > frustum.height()) return rect;
  auto tile = [&](double pixel, std::uint32_t tiles) {
    return std::uint32_t(std::clamp(std::floor(pixel / tile_size), 0.0, double(tiles - 1)));
  };
  rect.x0 = tile(px0, tiles_x);
  rect.x1 = tile(px1, tiles_x);
  rect.y0 = tile(py0, tiles_y);
  rect.y1 = tile(py1, tiles_y);
  return rect;
}

SubFrustum tile_sub_frustum(std::uint32_t tile, std::uint32_t tiles_x, std::uint32_t tile_size,
                            std::uint32_t width, std::uint32_t height, const double* depth,
                            const std::uint32_t* members_begin, const std::uint32_t* members_end) {
  SubFrustum f;
  f.x0 = double(tile % tiles_x) * tile_size;
  f.x1 = std::min(f.x0 + tile_size, double(width));
  f.y0 = double(tile / tiles_x) * tile_size;
  f.y1 = std::min(f.y0 + tile_size, double(height));
  f.near_depth = std::numeric_limits<double>::infinity();
  f.far_depth = -f.near_depth;
  for (const std::uint32_t* m = members_begin; m != members_end; ++m) {
    f.near_depth = std::min(f.near_depth, depth[*m]);
    f.far_depth = std::max(f.far_depth, depth[*m]);
  }
  return f;
}

std::uint64_t tile_key_bits(std::uint32_t tiles_x, std::uint32_t tiles_y) {
  return std::uint64_t(std::bit_width(std::max(tiles_x, 1u) - 1) +
                       std::bit_width(std::max(tiles_y, 1u) - 1));
}

AlgorithmOutput assign_lights_tiled(const Case& c, const ViewSamples& samples,
                                    std::uint32_t tile_size) {
  PhaseClock clock;
  const ViewFrustum frustum(c.camera);
  const std::uint32_t tiles_x = (samples.width + tile_size - 1) / tile_size;
  const std::uint32_t tiles_y = (samples.height + tile_size - 1) / tile_size;
  const std::uint32_t tile_count = tiles_x * tiles_y;
  const std::size_t n = samples.samples.size();

  // One cluster per tile with regular samples: the unique-cluster machinery with a constant key.
  std::vector<std::uint32_t> sample_tile(n, UniqueClusters::no_cluster), sample_key(n, 0);
  std::vector<double> depth(n, 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const ViewSample& sample = samples.samples[s];
      if (sample.sample_class != SampleClass::regular) continue;
      sample_tile[s] = (sample.pixel_y / tile_size) * tiles_x + sample.pixel_x / tile_size;
      depth[s] = frustum.depth(glm::dvec3(sample.position));
    }
  });
  const UniqueClusters tiles = find_unique_clusters(sample_tile, sample_key, tile_count);
  const std::size_t lists = tiles.keys.size();

  // Per tile: the min/max depth sub-frustum and the declared box around it and its samples.
  std::vector<SubFrustum> sub_frusta(lists);
  LightLists out;
  out.bounds.resize(lists);
  std::vector<std::uint32_t> grown(lists, 0);
  std::vector<std::uint32_t> list_of_tile(tile_count, UniqueClusters::no_cluster);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lists, 16), [&](const auto& r) {
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const std::uint32_t tile = tiles.tiles[t];
      list_of_tile[tile] = std::uint32_t(t);
      sub_frusta[t] = tile_sub_frustum(tile, tiles_x, tile_size, samples.width, samples.height,
                                       depth.data(), tiles.members.data() + tiles.member_offsets[t],
                                       tiles.members.data() + tiles.member_offsets[t + 1]);
      out.bounds[t] = frustum.bounding_box(sub_frusta[t]);
      for (std::uint32_t m = tiles.member_offsets[t]; m < tiles.member_offsets[t + 1]; ++m)
        grown[t] += grow_to_contain(out.bounds[t], samples.samples[tiles.members[m]].position);
    }
  });

  clock.lap(build_phase);

  // Light insertion into the covered tiles' candidate lists, in light order.
  std::vector<TileRect> rects(c.ranged_lights.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rects.size(), 4096), [&](const auto& r) {
    for (std::size_t l = r.begin(); l != r.end(); ++l)
      rects[l] = covered_tiles(frustum, c.ranged_lights[l], tile_size, tiles_x, tiles_y);
  });
  std::vector<std::uint64_t> candidate_offsets(lists + 1, 0);
  auto for_each_list = [&](const TileRect& rect, auto&& f) {
    for (std::uint32_t y = rect.y0; y <= rect.y1 && rect.x0 <= rect.x1; ++y)
      for (std::uint32_t x = rect.x0; x <= rect.x1; ++x)
        if (const std::uint32_t list = list_of_tile[y * tiles_x + x];
            list != UniqueClusters::no_cluster)
          f(list);
  };
  for (const TileRect& rect : rects)
    for_each_list(rect, [&](std::uint32_t list) { ++candidate_offsets[list + 1]; });
  for (std::size_t t = 0; t < lists; ++t) candidate_offsets[t + 1] += candidate_offsets[t];
  std::vector<std::uint32_t> candidates(candidate_offsets.back());
  {
    std::vector<std::uint64_t> fill(candidate_offsets.begin(), candidate_offsets.end() - 1);
    for (std::size_t l = 0; l < rects.size(); ++l)
      for_each_list(rects[l],
                    [&](std::uint32_t list) { candidates[fill[list]++] = std::uint32_t(l); });
  }

  // Per tile: the sub-frustum planes, then the exact sphere/box test against the declared box
  // (so that every listed light provably meets it).
  const ListWork work = build_light_lists(lists, out, [&](std::size_t t, auto& list) {
    ListWork w;
    for (std::uint64_t e = candidate_offsets[t]; e < candidate_offsets[t + 1]; ++e) {
      const RangedLight& light = c.ranged_lights[candidates[e]];
      ++w.light_tests;
      if (frustum.sphere_may_meet(sub_frusta[t], glm::dvec3(light.centre), light.range) &&
          geometry::sphere_meets_box(light.centre, light.range, out.bounds[t].min,
                                     out.bounds[t].max))
        list.push_back(candidates[e]);
    }
    return w;
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

}  // namespace shadowcts
