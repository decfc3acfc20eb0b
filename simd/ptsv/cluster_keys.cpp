#include "simd/ptsv/cluster_keys.h"

#include <algorithm>
#include <atomic>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowcts::simd::ptsv {

ClusterKeys assign_cluster_keys(const ref::ClusterKeyLayout& layout, const ref::ViewFrame& frame,
                                const PreparedScene& scene, bool require_pixel_wedge) {
  const ViewSamples& samples = scene.view_samples;
  const RegularSamples& regular = scene.samples;
  const std::vector<std::uint32_t>& index = regular.index;
  ClusterKeys keys;
  keys.key.assign(index.size(), ref::no_key);
  const std::uint64_t slice_limit = std::uint64_t(1) << layout.depth_bits;
  // slice_of_depth(z) is the k with slice_start(k) <= z < slice_start(k + 1) (slice_start grows
  // with k): the layout's table of the starts (make_cluster_key_layout's, up to 2^16 slices)
  // replaces its logarithm and powers per sample, with the very values it compares against;
  // layouts without one keep the per-sample search.
  static const std::vector<double> no_table;
  const std::vector<double>& start = layout.tables ? layout.tables->slice_start : no_table;
  const bool table = !start.empty();
  // interleave() places each bit of x, y and the slice independently: a key is the OR of the
  // three coordinates' own parts, tabled.
  std::vector<std::uint32_t> x_part(table ? layout.tiles_x : 0), y_part(table ? layout.tiles_y : 0),
      slice_part(table ? std::size_t(slice_limit) : 0);
  for (std::uint32_t x = 0; x < x_part.size(); ++x) x_part[x] = layout.interleave({x, 0, 0});
  for (std::uint32_t y = 0; y < y_part.size(); ++y) y_part[y] = layout.interleave({0, y, 0});
  for (std::uint32_t k = 0; k < slice_part.size(); ++k)
    slice_part[k] = layout.interleave({0, 0, k});
  std::atomic<bool> failed{false};
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, index.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          // The reference's per-sample steps, on the same position and pixel, read from the
          // prepared arrays (15 MB at gate_house.1M, against 83 MB of view samples): the pixel
          // is the sample's place in the row-major image.
          const ref::ViewPoint v = ref::to_view(frame, glm::dvec3(regular.position(i)));
          ref::ClusterCoordinate c;
          c.x = index[i] % samples.width / ref::cluster_tile_size;
          c.y = index[i] / samples.width / ref::cluster_tile_size;
          bool ok = v.depth > 0.0 && c.x < layout.tiles_x && c.y < layout.tiles_y;
          if (ok) {
            c.slice =
                table ? std::uint32_t(std::upper_bound(start.begin() + 1, start.end(), v.depth) -
                                      (start.begin() + 1))
                      : layout.slice_of_depth(v.depth);
            ok = c.slice < slice_limit;
          }
          if (ok && require_pixel_wedge)
            ok = ref::inside_pixel_wedge(
                frame, v, c.x * ref::cluster_tile_size, (c.x + 1) * ref::cluster_tile_size,
                c.y * ref::cluster_tile_size, (c.y + 1) * ref::cluster_tile_size);
          if (!ok) {
            failed.store(true, std::memory_order_relaxed);
            continue;
          }
          keys.key[i] =
              table ? x_part[c.x] | y_part[c.y] | slice_part[c.slice] : layout.interleave(c);
        }
      });
  if (failed.load()) {
    // Rare and not timed worth: the reference names the first sample, word for word.
    keys.problem = ref::assign_cluster_keys(layout, frame, samples, require_pixel_wedge).problem;
    if (keys.problem.empty()) keys.problem = "a view sample has no cluster key";
    keys.key.clear();
  }
  return keys;
}

std::vector<std::uint32_t> keys_per_view_sample(const PreparedScene& scene,
                                                const std::vector<std::uint32_t>& key) {
  return scene.per_view_sample(key, ref::no_key);
}

}  // namespace shadowcts::simd::ptsv
