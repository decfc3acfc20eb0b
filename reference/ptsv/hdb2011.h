#pragma once
// The 2011 PTSV (Sintorn, Olsson, Assarsson 2011; thesis Paper IV): the shadow volumes traverse a
// hierarchical depth buffer instead of the cluster hierarchy. The buffer is a full tree of 2D
// screen tiles with fan-out 32, children alternating 8x4 and 4x8 (Section 3.4), the finest tiles
// holding 8x4 samples; each tile keeps the min and max view depth of its regular samples (unlit
// samples are left out, Section 3.5), so a tile is the frustum cell of its pixels between the two
// depths (Figure 3). Algorithm 1: tiles are rejected, accepted (a bit in the hierarchical shadow
// buffer at that level) or refined; the finest level tests samples; merging ORs every accepted
// tile into its samples. Section 3.5's culling against the two 2D silhouette edges of the
// projected volume is applied with the planes through the eye (triangle_setup.h). The receiver
// half-space rule (receiver_rule.h) decides the sample tests, and a tile is accepted only where it
// cannot reject the caster for any of its samples (each tile keeps their largest reject reach).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "reference/ptsv/counters.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/triangle_setup.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

struct DepthTileLevel {
  std::uint32_t tile_width = 0, tile_height = 0;    // pixels per tile
  std::uint32_t child_columns = 0, child_rows = 0;  // 8x4 or 4x8 children (or samples)
  std::uint32_t columns = 0, rows = 0;              // tiles of this level
  std::vector<double> min_depth, max_depth;         // per tile, row-major
  std::vector<std::uint8_t> occupied;               // holds a regular sample
  std::vector<double> reject_reach;                 // the largest of the tile's samples
  std::vector<std::uint8_t> accepted;               // hierarchical shadow buffer
};

class HierarchicalDepthBuffer {
 public:
  // Throws InputError, or use problem(), when a regular sample lies behind the camera or outside
  // its finest tile's pixel wedge (the tile bounds would not contain it). Without a rule the
  // buffer only answers problem() (and the shape of its levels); traverse() needs one.
  HierarchicalDepthBuffer(const ViewFrame& frame, const ViewSamples& samples,
                          const ReceiverRule* rule);
  const std::string& problem() const { return problem_; }

  int level_count() const { return int(levels_.size()); }  // level 0: the root tile
  const DepthTileLevel& level(int l) const { return levels_[std::size_t(l)]; }

  // Algorithm 1 from the root for one volume.
  void traverse(const ShadowVolume& volume, const NodeTolerances& tolerances,
                std::vector<std::uint8_t>& shadowed, TraversalCounters& counters);
  // Merging the levels of the shadow buffer into the samples.
  void merge(std::vector<std::uint8_t>& shadowed) const;
  // The largest |coordinate| of an occupied tile's corner (for the node-test tolerances).
  double corner_bound() const;

 private:
  void traverse_tile(const ShadowVolume& volume, int level, std::uint32_t tx, std::uint32_t ty,
                     const NodeTolerances& tolerances, std::vector<std::uint8_t>& shadowed,
                     TraversalCounters& counters);
  FrustumCell tile_cell(int level, std::size_t tile, std::uint32_t tx, std::uint32_t ty) const;

  const ViewFrame& frame_;
  const ViewSamples& samples_;
  const ReceiverRule* rule_;
  std::vector<DepthTileLevel> levels_;
  static constexpr std::uint32_t no_sample = 0xFFFFFFFFu;
  std::vector<std::uint32_t> pixel_sample_;  // regular sample of each pixel, row-major
  std::string problem_;
};

}  // namespace shadowcts::ptsv
