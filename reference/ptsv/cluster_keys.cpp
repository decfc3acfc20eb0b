#include "reference/ptsv/cluster_keys.h"

#include <algorithm>
#include <cmath>

#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts::ptsv {
namespace {

int bits_for(std::uint64_t count) {
  int bits = 0;
  while ((std::uint64_t(1) << bits) < count) ++bits;
  return bits;
}

}  // namespace

double ClusterKeyLayout::slice_start(std::uint32_t k) const {
  if (tables && k < tables->slice_start.size()) return tables->slice_start[k];
  if (k == 0) return 0.0;
  return near * std::pow(slice_ratio, double(k));
}

std::uint32_t ClusterKeyLayout::slice_of_depth(double z) const {
  // Olsson 2012, eq. 2, then stepped so that slice_start(k) <= z < slice_start(k + 1) holds for
  // the very values the cells are built from (the logarithm may round across a boundary).
  const double estimate = std::floor(std::log(z / near) / std::log(slice_ratio));
  std::uint32_t k = estimate > 0.0 ? std::uint32_t(std::min(estimate, 4294967294.0)) : 0u;
  while (k > 0 && z < slice_start(k)) --k;
  while (k < 0xFFFFFFFEu && z >= slice_start(k + 1)) ++k;
  return k;
}

std::uint32_t ClusterKeyLayout::interleave(const ClusterCoordinate& c) const {
  std::uint32_t key = 0;
  int position = 0;
  const int most = std::max({x_bits, y_bits, depth_bits});
  for (int bit = 0; bit < most; ++bit) {
    if (bit < x_bits) key |= ((c.x >> bit) & 1u) << position++;
    if (bit < y_bits) key |= ((c.y >> bit) & 1u) << position++;
    if (bit < depth_bits) key |= ((c.slice >> bit) & 1u) << position++;
  }
  return key;
}

ClusterCoordinate ClusterKeyLayout::deinterleave(std::uint32_t key) const {
  ClusterCoordinate c;
  if (tables) {
    for (int b = 0; b < 4; ++b) {
      const ClusterCoordinate& part = tables->part[b][(key >> (8 * b)) & 0xFFu];
      c.x |= part.x;
      c.y |= part.y;
      c.slice |= part.slice;
    }
    return c;
  }
  int position = 0;
  const int most = std::max({x_bits, y_bits, depth_bits});
  for (int bit = 0; bit < most; ++bit) {
    if (bit < x_bits) c.x |= ((key >> position++) & 1u) << bit;
    if (bit < y_bits) c.y |= ((key >> position++) & 1u) << bit;
    if (bit < depth_bits) c.slice |= ((key >> position++) & 1u) << bit;
  }
  return c;
}

KeyLayoutResult make_cluster_key_layout(const Camera& camera, std::uint32_t width,
                                        std::uint32_t height) {
  KeyLayoutResult result;
  ClusterKeyLayout& layout = result.layout;
  layout.tiles_x = (width + cluster_tile_size - 1) / cluster_tile_size;
  layout.tiles_y = (height + cluster_tile_size - 1) / cluster_tile_size;
  layout.near = double(camera.near_plane);
  const double tan_half_fov = camera_frame(camera).tan_half_fov;
  layout.slice_ratio = 1.0 + 2.0 * tan_half_fov / double(layout.tiles_y);
  layout.x_bits = bits_for(layout.tiles_x);
  layout.y_bits = bits_for(layout.tiles_y);
  // Enough slices that the slice holding the far plane has a key.
  const double far_slice =
      std::floor(std::log(double(camera.far_plane) / layout.near) / std::log(layout.slice_ratio));
  if (!(far_slice < 4294967294.0)) {
    result.problem = "the near/far ratio needs more than 2^32 depth slices";
    return result;
  }
  layout.depth_slices = std::uint32_t(std::max(far_slice, 0.0)) + 1;
  layout.depth_bits = bits_for(layout.depth_slices);
  if (layout.key_bits() > key_bits_available)
    result.problem = "the cluster key needs " + std::to_string(layout.key_bits()) + " bits (" +
                     std::to_string(layout.x_bits) + " x + " + std::to_string(layout.y_bits) +
                     " y + " + std::to_string(layout.depth_bits) + " depth for " +
                     std::to_string(width) + "x" + std::to_string(height) + " and near/far " +
                     std::to_string(camera.near_plane) + "/" + std::to_string(camera.far_plane) +
                     "), the layout has " + std::to_string(key_bits_available);
  if (result.problem.empty()) {
    auto tables = std::make_shared<ClusterKeyTables>();
    if (layout.depth_bits <= 16)
      for (std::uint32_t k = 0; k <= (1u << layout.depth_bits); ++k)
        tables->slice_start.push_back(layout.slice_start(k));
    for (int b = 0; b < 4; ++b)
      for (std::uint32_t v = 0; v < 256; ++v)
        tables->part[b][v] = layout.deinterleave(v << (8 * b));
    layout.tables = std::move(tables);
  }
  return result;
}

ClusterKeys assign_cluster_keys(const ClusterKeyLayout& layout, const ViewFrame& frame,
                                const ViewSamples& samples, bool require_pixel_wedge) {
  ClusterKeys keys;
  keys.key.assign(samples.samples.size(), no_key);
  const std::uint64_t slice_limit = std::uint64_t(1) << layout.depth_bits;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular) continue;
    const ViewPoint v = to_view(frame, glm::dvec3(s.position));
    const std::string name = "view sample " + std::to_string(i);
    if (!(v.depth > 0.0)) {
      keys.problem = name + " does not lie in front of the camera";
      return keys;
    }
    ClusterCoordinate c;
    c.x = s.pixel_x / cluster_tile_size;
    c.y = s.pixel_y / cluster_tile_size;
    c.slice = layout.slice_of_depth(v.depth);
    if (c.x >= layout.tiles_x || c.y >= layout.tiles_y) {
      keys.problem = name + " has a pixel outside the " + std::to_string(samples.width) + "x" +
                     std::to_string(samples.height) + " image";
      return keys;
    }
    if (c.slice >= slice_limit) {
      keys.problem = name + " lies at view depth " + std::to_string(v.depth) +
                     ", beyond the last of the 2^" + std::to_string(layout.depth_bits) +
                     " depth slices the key layout derives from near/far: the case needs more "
                     "depth bits than the layout has";
      return keys;
    }
    if (require_pixel_wedge &&
        !inside_pixel_wedge(frame, v, c.x * cluster_tile_size, (c.x + 1) * cluster_tile_size,
                            c.y * cluster_tile_size, (c.y + 1) * cluster_tile_size)) {
      keys.problem = name +
                     " lies outside the view frustum of its 8x8 pixel tile, so implicit "
                     "cluster bounds cannot contain it";
      return keys;
    }
    keys.key[i] = layout.interleave(c);
  }
  return keys;
}

FrustumCell implicit_node_cell(const ClusterKeyLayout& layout, int level, std::uint32_t index) {
  const int free_bits = fanout_bits * (layout.mask_levels() - level);
  const std::uint64_t low = std::uint64_t(index) << free_bits;
  const std::uint64_t high = low | ((std::uint64_t(1) << free_bits) - 1);
  const std::uint64_t key_mask = (std::uint64_t(1) << layout.key_bits()) - 1;
  // Interleaving is monotone in every axis, so the smallest and largest keys under the prefix
  // give each axis' smallest and largest coordinate.
  const ClusterCoordinate lo = layout.deinterleave(std::uint32_t(low & key_mask));
  const ClusterCoordinate hi = layout.deinterleave(std::uint32_t(high & key_mask));
  FrustumCell cell;
  cell.x0 = lo.x * cluster_tile_size;
  cell.x1 = (hi.x + 1) * cluster_tile_size;
  cell.y0 = lo.y * cluster_tile_size;
  cell.y1 = (hi.y + 1) * cluster_tile_size;
  cell.depth0 = layout.slice_start(lo.slice);
  cell.depth1 = layout.slice_start(hi.slice + 1);
  return cell;
}

}  // namespace shadowcts::ptsv
