#pragma once
// The simd port of the per-fragment triangle setup (reference/softtile/fragment_occlusion.h,
// triangle_edges): one candidate triangle against every fragment of a tile, fragments in float
// lanes, each lane the reference's float operations in its order (glm's cross and dot, the sign
// applied by a multiplication), so the edge functions and the accept/reject decisions are the
// reference's bit for bit. fragment_occlusion.cpp is a Highway translation unit.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/softtile/fragment_occlusion.h"

namespace shadowcts::simd::softtile {

// A tile's fragment setups as structure of arrays, padded to a whole number of vectors.
struct FragmentArrays {
  std::vector<float> x, y, z, cos_rotation, sin_rotation;
  float inverse_scale = 1.0f;
  std::size_t size = 0;

  void assign(const std::vector<shadowcts::softtile::FragmentSetup>& fragments);
};

// The edge functions of one triangle (light-space vertices) for every fragment: for fragment j,
// accepted[j] is 1 (else 0) where triangle_edges() returns true, and then edges[(3 i + c) * stride
// + j] is component c (x, y, z) of edge i. stride >= the padded size of `fragments`.
void triangle_edges(const FragmentArrays& fragments, const std::array<glm::vec3, 3>& light_space,
                    std::uint32_t* accepted, float* edges, std::size_t stride);

// The padding FragmentArrays::assign uses: sizes are rounded up to a multiple of this.
inline constexpr std::size_t fragment_padding = 16;

}  // namespace shadowcts::simd::softtile
