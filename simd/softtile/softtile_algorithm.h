#pragma once
// simd `softtile`: the reference's tiles (reference/softtile/softtile_tile.h: relevant pixels,
// sphere/capsule bound, cone-culled caster list, fragment setups) over oneTBB, each pixel's
// candidates set up for all its fragments in float lanes (simd/softtile/fragment_occlusion.h), and
// the disk bitmask rasterized with Highway (rows in lanes, simd/softtile/disk_bitmask.h). Same
// masks, answers and counters as the reference for every variant.
#include <cstdint>
#include <memory>
#include <vector>

#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_tile.h"
#include "shadowcts/algorithm.h"
#include "simd/softtile/disk_bitmask.h"
#include "simd/softtile/fragment_occlusion.h"

namespace shadowcts {

// id "softtile", backend "simd", the reference's variants and budgets.
std::unique_ptr<Algorithm> make_simd_softtile();

namespace simd::softtile {

// One prepared tile rasterized: a mask per pixel (Tile::pixels order) and the reference's
// per-tile work counters.
struct TileRaster {
  std::vector<DiskRows> masks;
  std::uint64_t tests = 0, rasterized = 0, rasterized_max = 0;
};

// Scratch reused across the tiles of one thread.
struct TileScratch {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint32_t> order;  // the tile's fragments by light-space height
  std::vector<shadowcts::softtile::FragmentSetup> sorted;
  std::vector<std::uint32_t> receivers;
  FragmentArrays fragments;
  std::vector<DiskRows> masks;
  std::vector<std::uint64_t> rasterized;  // per fragment, in `order`
};

void rasterize_tile(const ViewSamples& samples, const shadowcts::softtile::Gathered& gathered,
                    const DiskRaster& raster, const shadowcts::softtile::Tile& tile,
                    TileScratch& scratch, TileRaster& out);

}  // namespace simd::softtile
}  // namespace shadowcts
