#pragma once
// Cluster keys (Sintorn 2014, Section 2, eq. 1 and Figure 2): a view sample at pixel (x, y) and
// view depth z lies in the cluster (x / 8, y / 8, k) with k the exponential depth slice of
// clustered shading (Olsson 2012, eq. 1-2): slice k starts at near * (1 + 2 tan(fov / 2) / S_y)^k,
// S_y being the number of tile rows, so a cluster is about as deep as it is wide. The three
// integer coordinates are interleaved in Morton order into the key; the hierarchy's levels are
// its 5-bit groups.
//
// The paper's layout is 1024^2 pixels and 23 bits (7 + 7 + 9, the two extra depth bits on top).
// Generalized: each axis gets the bits its range needs (depth: from the near/far ratio), bits are
// interleaved x, y, depth from the least significant end while an axis has bits left (so an axis
// with more bits keeps its top bits above the others', as in Figure 2), and a case that needs more
// than the 32 bits of the key is refused, never wrapped around.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reference/ptsv/view_frame.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

inline constexpr std::uint32_t cluster_tile_size = 8;  // pixels per tile side
inline constexpr int key_bits_available = 32;
inline constexpr int fanout_bits = 5;  // 32 children per node
inline constexpr std::uint32_t no_key = 0xFFFFFFFFu;

struct ClusterCoordinate {
  std::uint32_t x = 0, y = 0, slice = 0;
};

struct ClusterKeyTables;

struct ClusterKeyLayout {
  std::uint32_t tiles_x = 0, tiles_y = 0;
  std::uint32_t depth_slices = 0;  // slices from the near plane to the one holding the far plane
  int x_bits = 0, y_bits = 0, depth_bits = 0;
  double near = 0.0;
  double slice_ratio = 1.0;  // 1 + 2 tan(fov / 2) / tiles_y

  int key_bits() const { return x_bits + y_bits + depth_bits; }
  // Levels 0 .. mask_levels() - 1 hold child masks; the clusters are level mask_levels().
  int mask_levels() const {
    const int levels = (key_bits() + fanout_bits - 1) / fanout_bits;
    return levels > 0 ? levels : 1;
  }
  // The view depth where slice k starts; slice 0 reaches down to the camera so that samples
  // rounded just in front of the near plane still have a cell.
  double slice_start(std::uint32_t k) const;
  // The slice holding view depth z > 0 (may be >= 2^depth_bits: the caller checks).
  std::uint32_t slice_of_depth(double z) const;

  std::uint32_t interleave(const ClusterCoordinate& c) const;
  ClusterCoordinate deinterleave(std::uint32_t key) const;

  // Set by make_cluster_key_layout: slice_start and deinterleave answered from tables of their
  // own values (a node test of the implicit bounds asks for both, twice, per child). Without
  // them (a layout put together by hand) they compute.
  std::shared_ptr<const ClusterKeyTables> tables;
};

struct ClusterKeyTables {
  std::vector<double> slice_start;  // of slices 0 .. 2^depth_bits, for depth_bits <= 16
  // deinterleave places each key bit independently: a key's coordinates are the OR of the parts
  // of its four bytes, part[b][v] = deinterleave(v << 8 b).
  ClusterCoordinate part[4][256];
};

// The layout for a camera and an image of width x height samples, or why there is none (the
// case needs more key bits than there are).
struct KeyLayoutResult {
  ClusterKeyLayout layout;
  std::string problem;  // empty: fine
};
KeyLayoutResult make_cluster_key_layout(const Camera& camera, std::uint32_t width,
                                        std::uint32_t height);

// The key of every regular sample (no_key for the others), or the first sample the layout cannot
// hold: in front of the camera, beyond the last representable depth slice, or (when
// require_pixel_wedge, for implicit bounds) outside the lateral wedge of its own tile.
struct ClusterKeys {
  std::vector<std::uint32_t> key;
  std::string problem;  // empty: every regular sample has a key
};
ClusterKeys assign_cluster_keys(const ClusterKeyLayout& layout, const ViewFrame& frame,
                                const ViewSamples& samples, bool require_pixel_wedge);

// The frustum cell that a node of the hierarchy covers: level in [0, mask_levels()], index the
// node's key prefix (the cluster key shifted right by 5 * (mask_levels() - level)).
FrustumCell implicit_node_cell(const ClusterKeyLayout& layout, int level, std::uint32_t index);

}  // namespace shadowcts::ptsv
