#pragma once
// Tiled light assignment (Paper I): 32 x 32 (a parameter) screen tiles; each tile's sub-frustum
// spans its pixels and the min/max view depth of its samples (Section 6.3's depth range
// optimization); every light is inserted into the tiles its screen-space bounding rectangle
// covers (Section 6.1), then tested against the tile's sub-frustum planes and, exactly, against
// the tile's declared box. Deferred and forward (with a depth pre-pass) read the same depths
// here, so they produce the same lists.
#include <cstdint>

#include "shadowcts/algorithm.h"

namespace shadowcts {

class ViewFrustum;
struct SubFrustum;

struct TileRect {
  std::uint32_t x0 = 1, x1 = 0, y0 = 1, y1 = 0;  // inclusive tile ranges; empty when x0 > x1
};

// The tiles that the screen-space bounding rectangle of a light's sphere covers (shared with the
// simd port, whose candidate lists must be the same).
TileRect covered_tiles(const ViewFrustum& frustum, const RangedLight& light,
                       std::uint32_t tile_size, std::uint32_t tiles_x, std::uint32_t tiles_y);

// Tile `tile`'s sub-frustum (Section 6.3): its pixels (the last row and column of tiles clipped to
// the image) and the min/max of depth[m] over its member samples m.
SubFrustum tile_sub_frustum(std::uint32_t tile, std::uint32_t tiles_x, std::uint32_t tile_size,
                            std::uint32_t width, std::uint32_t height, const double* depth,
                            const std::uint32_t* members_begin, const std::uint32_t* members_end);

// The bits of a tile index (x, y): the key_bits counter of every tiled backend.
std::uint64_t tile_key_bits(std::uint32_t tiles_x, std::uint32_t tiles_y);

AlgorithmOutput assign_lights_tiled(const Case& c, const ViewSamples& samples,
                                    std::uint32_t tile_size);

}  // namespace shadowcts
