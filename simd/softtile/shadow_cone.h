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
#include "shadowcts/huge_pages.h"

namespace shadowcts::simd::softtile {

// In huge pages where large (a million triangles: 40 MB; a fresh 4 KiB page costs a fault,
// huge_pages.h).
struct ConeArrays {
  HugePageVector<double> tip[3], start_height;
  HugePageVector<double> tip_length;  // glm::length(tip), as the reference's height slack takes it
};

// Nodes of the cone tree hold this many triangles (leaves) or child nodes.
inline constexpr std::size_t tree_arity = 8;

// Nodes of one level of the cone tree. A node's cone (same axis and angle as the triangles', its
// tip placed so that it holds the tip, hence the cone, of every triangle below it; placed over a
// ball around those tips, not over the child nodes' cone tips, which lie higher) lets a tile skip
// all the triangles below it when its bound lies farther outside the node's cone than every
// triangle's slack plus rounding allows: then each one's may_shadow is provably false (see
// cull_candidates).
struct ConeGroups {
  // Per node: its cone's tip and |tip|, and the largest distance from it to a triangle's tip below
  // it (infinite where a tip below is not finite: such a node is never skipped).
  std::vector<double> tip[3], tip_length, spread;
};

// The gathered triangles' cones in the Morton order of their tips (non-finite tips last), under a
// tree_arity-ary tree of group cones: levels[0] has a node per tree_arity consecutive triangles,
// levels[k + 1] one per tree_arity consecutive nodes of levels[k], the last level at most
// tree_arity nodes. A tile walks it from the top, so that it tests the cones of the triangles near
// its bound, not those of every triangle of every cluster near it.
struct ConeTree {
  ConeArrays triangles;                 // in tree order
  HugePageVector<std::uint32_t> index;  // tree order -> index into Gathered::triangles
  std::vector<ConeGroups> levels;
};

// The gathered cones as structure of arrays, and the sun.
struct GatheredCones {
  ConeArrays clusters;
  HugePageVector<std::uint32_t> cluster_of;  // per gathered triangle, its cluster
  ConeTree tree;
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
