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

// The gathered cones as structure of arrays, and the sun.
struct GatheredCones {
  ConeArrays clusters, triangles;
  std::vector<std::uint32_t> first, count;  // per cluster: its range of triangles
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
