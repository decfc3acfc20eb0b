#pragma once
// The post's per-fragment step: project each candidate triangle into disk space and clear its
// cells from the fragment's disk bitmask. In float, as the shader does.
#include <array>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "reference/softtile/disk_bitmask.h"

namespace shadowcts::softtile {

struct FragmentSetup {
  glm::vec3 position;   // the fragment in light space
  float inverse_scale;  // 1 / tan(a) (cone-exact) or 1 / sin(a) (the post)
  // disk_reach_per_height(inverse_scale); infinity: no early-out by the light-space box.
  float reach_per_height = std::numeric_limits<float>::infinity();
  float cos_rotation = 1.0f, sin_rotation = 0.0f;  // the grid's rotation for this fragment
};

// The three edge functions of the triangle (light-space vertices) seen from the fragment, in
// disk space, oriented so that the projection of the part of the triangle in front of the
// fragment is where all three are >= 0; false when the triangle cannot touch the disk (behind the
// fragment, seen edge-on, or one edge's outside contains the whole unit disk). First of all, a
// triangle whose light-space box lies beside the disk's reach (shadowcts/geometry/disk_reach.h)
// is rejected without a setup: it covers no cell, and most candidates of a tile are such.
//
// The post divides by z and flips each 2D edge equation by the sign of z; here the edge functions
// are written homogeneously, E_ij = s (h_i x h_j) with h = (x / scale, y / scale, z) and s the sign
// of det(h0, h1, h2), which is the same thing without the division: h_i x h_j = z_i z_j times the
// 2D edge equation through the projected vertices, so a vertex behind the fragment flips exactly
// the edges the post's xor mask flips, and no vertex is ever divided by z = 0.
bool triangle_edges(const FragmentSetup& fragment, const std::array<glm::vec3, 3>& light_space,
                    std::array<glm::vec3, 3>& edges);

}  // namespace shadowcts::softtile
