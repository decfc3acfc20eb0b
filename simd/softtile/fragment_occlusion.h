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
#include "simd/softtile/disk_bitmask.h"

namespace shadowcts::simd::softtile {

// Fragments in blocks of this many consecutive ones (a whole number of vectors on every target
// but those wider than 16 floats, where blocks are not used).
inline constexpr std::size_t fragment_block = 16;

// A tile's fragment setups as structure of arrays, with each fragment's receiver triangle, padded
// to a whole number of 64-bit words of fragments, and per block of fragments the bounds that
// decide a whole block at once (NaN ignored): the lowest light-space z (+inf for a block of NaN
// only), the x and y ranges and the largest |x| + |y| (disk_reach.h), padded to a multiple of 16
// blocks with blocks that no triangle reaches.
struct FragmentArrays {
  std::vector<float> x, y, z, cos_rotation, sin_rotation;
  std::vector<std::uint32_t> receiver;
  // The distinct receivers, ascending, and how many fragments lie on each, padded to a multiple
  // of 16 entries with count 0 (a triangle never shadows its own receiver: these are the tests
  // the reference does not make).
  std::vector<std::uint32_t> receiver_ids, receiver_counts;
  std::vector<float> block_lowest_z, block_x0, block_x1, block_y0, block_y1, block_coordinates;
  float inverse_scale = 1.0f;
  float reach_per_height = 1.0f;
  std::size_t size = 0;
  bool rotated = false;  // some fragment's grid is rotated (cos_rotation != 1 or sin_rotation != 0)

  void assign(const std::vector<shadowcts::softtile::FragmentSetup>& fragments,
              const std::vector<std::uint32_t>& receivers);
  std::size_t words() const { return (size + 63) / 64; }
  std::size_t blocks() const { return (size + fragment_block - 1) / fragment_block; }
};

// The edge functions of one triangle (light-space vertices, its id `triangle`) for every
// fragment: bit j % 64 of accepted[j / 64] is set where the fragment's receiver is not `triangle`
// and triangle_edges() returns true, and then edges[(3 i + c) * stride + j] is component c (x, y,
// z) of edge i (elsewhere edges holds anything). Returns how many fragments' receiver is not
// `triangle` (the reference's pixel-triangle tests). stride >= the padded size of `fragments`;
// accepted has fragments.words() words. The intermediate result the port's test diffs against the
// reference bit for bit; occlude_fragments() runs the same per-vector code.
std::size_t triangle_edges(const FragmentArrays& fragments,
                           const std::array<glm::vec3, 3>& light_space, std::uint32_t triangle,
                           std::uint64_t* accepted, float* edges, std::size_t stride);

// The triangle (light-space vertices, its id `triangle`) cleared from masks[j] of every fragment j
// that accepts it, as triangle_edges() and then DiskRaster::clear_triangles() would, and counted
// in rasterized[j]; returns triangle_edges()'s count of tests. A block of fragments that no
// fragment of can accept is only counted: every vertex lies behind it (vertex z <= the block's
// lowest z), or the triangle's box lies beside the reach of the disk of a fragment at the block's
// bounds (disk_reach.h: every bound is monotone, so then it lies beside every fragment's).
std::size_t occlude_fragments(const FragmentArrays& fragments,
                              const std::array<glm::vec3, 3>& light_space, std::uint32_t triangle,
                              const DiskRaster& raster, DiskRows* masks, std::uint64_t* rasterized);

// The padding FragmentArrays::assign uses: sizes are rounded up to a multiple of this.
inline constexpr std::size_t fragment_padding = 64;

}  // namespace shadowcts::simd::softtile
