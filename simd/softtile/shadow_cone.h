#pragma once
// The simd port of the tile's cone culling (reference/softtile/shadow_cone.cpp, may_shadow, as
// reference/softtile/softtile_tile.cpp's cull_candidates applies it): many cones against one
// tile bound in double lanes, every lane the reference's double operations in the reference's
// order (the sine and cosine of the disk's radius, constant per case, computed once in scalar),
// so the candidate lists are the reference's. shadow_cone.cpp is a Highway translation unit.
#include <cstdint>
#include <vector>

#include "reference/softtile/shadow_cone.h"
#include "reference/softtile/softtile_gather.h"

namespace shadowcts::simd::softtile {

struct ConeArrays {
  std::vector<double> tip[3], start_height;
  std::vector<double> tip_length;  // glm::length(tip), as the reference's height slack takes it
};

// Consecutive clusters per group. A group's cone (same axis and angle, its tip placed so that the
// cone holds every member's tip, hence every member's cone) lets a tile skip all of them when its
// bound lies farther outside the group's cone than every member's slack plus rounding: then each
// member's may_shadow is provably false (see gathered_cones).
inline constexpr std::size_t cluster_group = 16;
// Groups of cluster_group groups (256 clusters), tested first.
inline constexpr std::size_t cluster_super_group = 16 * cluster_group;
// Consecutive triangles of one cluster per group, the same way.
inline constexpr std::size_t triangle_group = 8;

struct ConeGroups {
  // Per group: the group cone's tip, the largest distance from it to a member's tip, and whether
  // the group may be skipped at all (every member's tip finite).
  std::vector<double> tip[3], spread;
  std::vector<std::uint8_t> skippable;

  // Adds the group of cones [begin, end) of `cones`.
  void add(const ConeArrays& cones, std::size_t begin, std::size_t end, const double direction[3],
           double sin_radius);
};

// The gathered cones as structure of arrays, and the sun.
struct GatheredCones {
  ConeArrays clusters, triangles;
  std::vector<std::uint32_t> first, count;  // per cluster: its range of triangles
  ConeGroups cluster_super_groups;          // of cluster_super_group clusters
  ConeGroups cluster_groups;                // of cluster_group clusters
  ConeGroups triangle_groups;  // of triangle_group triangles, from each cluster's first
  std::vector<std::uint32_t> first_triangle_group;  // per cluster
  double direction[3] = {0, 0, 1};
  double cos_radius = 1.0, sin_radius = 0.0;
};

GatheredCones gathered_cones(const shadowcts::softtile::Gathered& gathered);

// shadowcts::softtile::cull_candidates for `bound`: replaces `candidates` with every triangle
// (index into Gathered::triangles) of every cluster whose cone may shadow the bound and whose own
// cone may, in gathered order.
void cull_candidates(const GatheredCones& cones, const shadowcts::softtile::TileBound& bound,
                     std::vector<std::uint32_t>& candidates);

}  // namespace shadowcts::simd::softtile
