#include "reference/ptsv/hdb2011.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace shadowcts::ptsv {

HierarchicalDepthBuffer::HierarchicalDepthBuffer(const ViewFrame& frame, const ViewSamples& samples,
                                                 const ReceiverRule* rule)
    : frame_(frame), samples_(samples), rule_(rule) {
  const std::uint32_t width = samples.width, height = samples.height;
  // Bottom-up: 8x4 samples per finest tile, then 4x8 tiles, 8x4, ... until one tile covers all.
  std::vector<DepthTileLevel> bottom_up;
  DepthTileLevel level;
  level.child_columns = 8;
  level.child_rows = 4;
  level.tile_width = 8;
  level.tile_height = 4;
  for (;;) {
    level.columns = (width + level.tile_width - 1) / level.tile_width;
    level.rows = (height + level.tile_height - 1) / level.tile_height;
    bottom_up.push_back(level);
    if (level.columns <= 1 && level.rows <= 1) break;
    const bool wide = level.child_columns == 8;
    level.child_columns = wide ? 4 : 8;
    level.child_rows = wide ? 8 : 4;
    level.tile_width *= level.child_columns;
    level.tile_height *= level.child_rows;
  }
  levels_.assign(bottom_up.rbegin(), bottom_up.rend());
  for (DepthTileLevel& l : levels_) {
    const std::size_t tiles = std::size_t(l.columns) * l.rows;
    l.min_depth.assign(tiles, std::numeric_limits<double>::infinity());
    l.max_depth.assign(tiles, -std::numeric_limits<double>::infinity());
    l.occupied.assign(tiles, 0);
    l.reject_reach.assign(tiles, 0.0);
    l.accepted.assign(tiles, 0);
  }
  const DepthTileLevel& finest = levels_.back();
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular) continue;
    const ViewPoint v = to_view(frame, glm::dvec3(s.position));
    const std::uint32_t fx = s.pixel_x / finest.tile_width, fy = s.pixel_y / finest.tile_height;
    if (s.pixel_x >= width || s.pixel_y >= height ||
        !inside_pixel_wedge(frame, v, fx * finest.tile_width, (fx + 1) * finest.tile_width,
                            fy * finest.tile_height, (fy + 1) * finest.tile_height)) {
      problem_ = "view sample " + std::to_string(i) +
                 " lies behind the camera or outside the view frustum of its 8x4 pixel tile, so "
                 "the depth-buffer tiles cannot contain it";
      return;
    }
    for (DepthTileLevel& l : levels_) {
      const std::size_t tile =
          std::size_t(s.pixel_y / l.tile_height) * l.columns + s.pixel_x / l.tile_width;
      l.min_depth[tile] = std::min(l.min_depth[tile], v.depth);
      l.max_depth[tile] = std::max(l.max_depth[tile], v.depth);
      l.occupied[tile] = 1;
      if (rule) l.reject_reach[tile] = std::max(l.reject_reach[tile], rule->reject_reach()[i]);
    }
  }
  // Pixel -> sample, for the finest level's sample tests.
  pixel_sample_.assign(std::size_t(width) * height, no_sample);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class == SampleClass::regular)
      pixel_sample_[std::size_t(s.pixel_y) * width + s.pixel_x] = std::uint32_t(i);
  }
}

FrustumCell HierarchicalDepthBuffer::tile_cell(int level, std::size_t tile, std::uint32_t tx,
                                               std::uint32_t ty) const {
  const DepthTileLevel& l = levels_[std::size_t(level)];
  FrustumCell cell;
  cell.x0 = tx * l.tile_width;
  cell.x1 = cell.x0 + l.tile_width;
  cell.y0 = ty * l.tile_height;
  cell.y1 = cell.y0 + l.tile_height;
  cell.depth0 = l.min_depth[tile];
  cell.depth1 = l.max_depth[tile];
  return cell;
}

double HierarchicalDepthBuffer::corner_bound() const {
  double bound = 0.0;
  for (int l = 1; l < level_count(); ++l) {
    const DepthTileLevel& level = levels_[std::size_t(l)];
    for (std::uint32_t ty = 0; ty < level.rows; ++ty)
      for (std::uint32_t tx = 0; tx < level.columns; ++tx) {
        const std::size_t tile = std::size_t(ty) * level.columns + tx;
        if (!level.occupied[tile]) continue;
        for (const glm::dvec3& corner : cell_corners(frame_, tile_cell(l, tile, tx, ty)))
          bound = std::max({bound, std::fabs(corner.x), std::fabs(corner.y), std::fabs(corner.z)});
      }
  }
  return bound;
}

void HierarchicalDepthBuffer::traverse(const ShadowVolume& volume, const NodeTolerances& tolerances,
                                       std::vector<std::uint8_t>& shadowed,
                                       TraversalCounters& counters) {
  if (!rule_) throw std::logic_error("ptsv: a depth buffer without the receiver rule traversed");
  if (levels_.front().occupied[0]) traverse_tile(volume, 0, 0, 0, tolerances, shadowed, counters);
}

void HierarchicalDepthBuffer::traverse_tile(const ShadowVolume& volume, int level, std::uint32_t tx,
                                            std::uint32_t ty, const NodeTolerances& tolerances,
                                            std::vector<std::uint8_t>& shadowed,
                                            TraversalCounters& counters) {
  ++counters.nodes_visited;
  const DepthTileLevel& l = levels_[std::size_t(level)];
  if (level + 1 == level_count()) {
    // TESTVIEWSAMPLE on every lane: the tile's samples.
    for (std::uint32_t r = 0; r < l.child_rows; ++r)
      for (std::uint32_t c = 0; c < l.child_columns; ++c) {
        const std::uint32_t px = tx * l.child_columns + c, py = ty * l.child_rows + r;
        if (px >= samples_.width || py >= samples_.height) continue;
        const std::uint32_t s = pixel_sample_[std::size_t(py) * samples_.width + px];
        if (s == no_sample) continue;
        ++counters.sample_tests;
        const ViewSample& sample = samples_.samples[s];
        if (sample_in_volume(volume, sample) && !shadowed[s] &&
            rule_->caster_counts(volume, sample))
          shadowed[s] = 1;
      }
    return;
  }
  // TESTTRIVOLUME on every lane (Algorithm 2), then the refine queue.
  DepthTileLevel& children = levels_[std::size_t(level) + 1];
  std::uint32_t queue = 0;
  for (std::uint32_t lane = 0; lane < 32; ++lane) {
    const std::uint32_t cx = tx * l.child_columns + lane % l.child_columns;
    const std::uint32_t cy = ty * l.child_rows + lane / l.child_columns;
    if (cx >= children.columns || cy >= children.rows) continue;
    const std::size_t tile = std::size_t(cy) * children.columns + cx;
    if (!children.occupied[tile]) continue;  // only unlit samples: left out of the buffer
    const NodeVerdict verdict = classify_node(
        volume, cell_corners(frame_, tile_cell(level + 1, tile, cx, cy)), tolerances,
        CullingPlanes::silhouette, counters, [&] { return children.reject_reach[tile]; });
    if (verdict == NodeVerdict::accept) children.accepted[tile] = 1;  // UPDATESHADOWBUFFER
    if (verdict == NodeVerdict::refine) queue |= 1u << lane;
  }
  for (std::uint32_t lane = 0; lane < 32; ++lane)
    if (queue & (1u << lane))
      traverse_tile(volume, level + 1, tx * l.child_columns + lane % l.child_columns,
                    ty * l.child_rows + lane / l.child_columns, tolerances, shadowed, counters);
}

void HierarchicalDepthBuffer::merge(std::vector<std::uint8_t>& shadowed) const {
  for (std::size_t i = 0; i < samples_.samples.size(); ++i) {
    const ViewSample& s = samples_.samples[i];
    if (s.sample_class != SampleClass::regular) continue;
    for (const DepthTileLevel& l : levels_) {
      const std::size_t tile =
          std::size_t(s.pixel_y / l.tile_height) * l.columns + s.pixel_x / l.tile_width;
      if (l.accepted[tile]) shadowed[i] = 1;
    }
  }
}

}  // namespace shadowcts::ptsv
