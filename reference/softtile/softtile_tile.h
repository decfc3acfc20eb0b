#pragma once
// One 16 x 16 pixel tile of the eval pass, up to its rasterization: the tile's relevant pixels,
// their bound (sphere or tapered capsule), the candidate list (cluster cones, then the surviving
// clusters' triangle cones) and each pixel's fragment setup (light-space position, disk scale,
// grid rotation). The definition of the per-tile caster lists every softtile backend reproduces.
#include <cstdint>
#include <vector>

#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/shadow_cone.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::softtile {

inline constexpr int tile_size = 16;

struct Tile {
  std::vector<std::size_t> pixels;        // view-sample indices of the relevant samples
  TileBound bound;                        // of their positions
  std::vector<std::uint32_t> candidates;  // into Gathered::triangles, in gathered order
  std::vector<FragmentSetup> fragments;   // per pixel
};

// The frame's tiles: tiles_x columns of tiles, row-major.
inline std::uint32_t tiles_across(std::uint32_t pixels) {
  return (pixels + tile_size - 1) / tile_size;
}

// 1 / tan(a) (cone-exact) or 1 / sin(a) (the post), in float as the shader holds it.
float disk_inverse_scale(const Gathered& gathered, const Variant& variant);

// A per-pixel rotation angle in [0, 2 pi): a hash of the seed and the pixel, so every run and
// every thread count gives the same grid.
double rotation_angle(std::uint64_t seed, std::uint32_t x, std::uint32_t y);

// Fills `tile` for tile number `index`; false (and no candidates) when it has no relevant pixel.
// prepare_tile_pixels() and then cull_candidates().
bool prepare_tile(const Case& c, const ViewSamples& samples, const Gathered& gathered,
                  const Variant& variant, float inverse_scale, std::size_t index, Tile& tile);

// The tile's pixels, bound and fragment setups; clears its candidates. False without pixels.
bool prepare_tile_pixels(const Case& c, const ViewSamples& samples, const Gathered& gathered,
                         const Variant& variant, float inverse_scale, std::size_t index,
                         Tile& tile);

// The tile's candidate list against its bound: every cluster whose cone may_shadow() it, then
// those of its triangles whose cones do, in gathered order.
void cull_candidates(const Gathered& gathered, Tile& tile);

}  // namespace shadowcts::softtile
