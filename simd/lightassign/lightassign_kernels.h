#pragma once
// The Highway part of the simd `lightassign`, dispatched at run time to the best target
// (lightassign_kernels.cpp is the one translation unit foreach_target compiles per target). Each
// kernel takes one list's volume and tests many lights against it in lanes, with the reference's
// float/double operations in the reference's order, so every decision equals the reference's.
#include <cstdint>
#include <vector>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/light_list_builder.h"
#include "shadowcts/algorithm.h"
#include "simd/lightassign/light_bvh.h"

namespace shadowcts::simd {

// The light BVH's build steps (light_bvh.h), each the reference's operations in lanes:
// LightBvh's 63-bit Morton code of each light's centre over the centres' box (low, extent per
// axis) into code[i], the lights' spheres packed as (centre x, y, z, range) in `sphere`;
void morton_codes(const float* sphere, std::size_t count, const double* low, const double* extent,
                  std::uint64_t* code);
// the boxes of nodes [first, first + count) of the first level around their 32 leaves' boxes
// (each sphere's float box rounded outwards), from bvh.sphere;
void leaf_node_boxes(const LightBvhLanes& bvh, std::size_t first, std::size_t count,
                     BoxArrays& level);
// the boxes of nodes [first, first + count) of a level above around their 32 children each.
void node_boxes(const BoxArrays& children, std::size_t first, std::size_t count, BoxArrays& level);

// Clustered: the depth-first traversal of LightBvh::traverse over the cluster box (32 children
// against the box per node, in lanes), then for the leaves whose boxes overlap it the exact
// sphere/box cull (the reference's double filter in lanes, undecided pairs exactly). Appends the
// lights that meet the box in Morton order; reports nodes_tested and light_tests as the
// reference does.
ListWork query_light_bvh(const LightBvhLanes& bvh, const Aabb& box,
                         std::vector<std::uint32_t>& list);

// The brute force of the baseline (bench/lightassign_simd_bench.cpp): every light against
// the box by the leaf tests of query_light_bvh, no node tested; the same list in the same (Morton)
// order. nodes_tested counts the lights, light_tests those whose leaf box overlaps.
ListWork test_every_light(const LightBvhLanes& bvh, const Aabb& box,
                          std::vector<std::uint32_t>& list);

// The camera frame of ViewFrustum (the same glm operations on the same inputs give the same
// doubles): to_view(p) = (dot(p - origin, right), dot(p - origin, up), dot(p - origin, forward)).
struct ViewFrame {
  double origin[3], right[3], up[3], forward[3];
  explicit ViewFrame(const Camera& camera);
};

// Per tile: ViewFrustum::sphere_may_meet's quantities for the tile's sub-frustum, and its box.
struct TileVolume {
  double near_depth = 0, far_depth = 0;
  // The four side planes (along = slope * depth), with along = x, -x, -y, y and the slopes
  // sx0, -sx1, -sy0, sy1; norm = sqrt(1 + slope^2).
  double slope[4] = {0, 0, 0, 0}, norm[4] = {1, 1, 1, 1};
  double origin_length = 0;  // |eye|
  Aabb box;
};

// Tiled: each candidate (light indices, in order) against the tile's sub-frustum planes
// (ViewFrustum::sphere_may_meet, its view coordinates and lengths computed in lanes with
// ViewFrustum's operations in their order) and, exactly, the tile's box; appends those that
// pass, in order.
// light_tests counts the candidates.
ListWork cull_tile_candidates(const std::vector<RangedLight>& lights, const ViewFrame& frame,
                              const TileVolume& tile, const std::uint32_t* candidates,
                              std::size_t count, std::vector<std::uint32_t>& list);

// ClusterGrid::slice_of as a table lookup: slice_of is floor(log(depth / near) / log(base)), so
// a depth certainly lies in slice k when it is within [near_k, near_{k+1}) by more than 1e-10
// (relative) of either end, far above the few ulps by which the logarithms and slice_near can
// round. A float logarithm in lanes guesses k, the table confirms it, and the depths it does not
// confirm (near a boundary, NaN, or a guess off by one) take the reference's own slice_of.
struct SliceTable {
  explicit SliceTable(const ClusterGrid& grid);

  const ClusterGrid* grid;
  double inverse_near;
  float inverse_log_base;
  std::uint32_t last;  // slices - 1
  // Per slice k: the depths certainly in it are [low[k], high[k]); empty when the grid has too
  // many slices for a table (then every depth takes slice_of).
  std::vector<double> low, high;
};

// The cluster keys of `count` regular samples of one pixel row (positions x, y, z, pixel indices
// `index`, the row's first pixel `row_pixel`): key[i] = tile_key_of_x[index[i] - row_pixel] |
// slice << slice_shift, the slice of the sample's view depth (ViewFrustum::depth's doubles) by
// `slices`. deepest becomes std::max of itself and every depth (NaN ignored, as std::max does).
void row_cluster_keys(const ViewFrame& frame, const SliceTable& slices, int slice_shift,
                      const std::uint32_t* tile_key_of_x, std::uint32_t row_pixel,
                      const std::uint32_t* index, const float* x, const float* y, const float* z,
                      std::size_t count, std::uint32_t* key, double& deepest);

}  // namespace shadowcts::simd
