#include "simd/softtile/softtile_algorithm.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include <hwy/contrib/sort/vqsort.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/softtile/counters.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "simd/softtile/shadow_cone.h"
#include "simd/softtile/softtile_gather.h"

namespace shadowcts::simd {
namespace softtile {

namespace ref = shadowcts::softtile;

void rasterize_tile(const ViewSamples& samples, const ref::Gathered& gathered,
                    const DiskRaster& raster, const ref::Tile& tile, TileScratch& scratch,
                    TileRaster& out) {
  const std::size_t n = tile.pixels.size();
  out.tests = out.rasterized = out.rasterized_max = 0;
  // The fragments in order of light-space height, so that each block of 16 spans few heights and
  // more blocks lie wholly above a candidate, which none of their fragments can then accept
  // (occlude_fragments). Where a fragment sits changes neither its mask nor its counts. Keys: the
  // height's bits made orderable as unsigned (-0 below +0, NaN above everything), then the pixel.
  scratch.keys.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const float z = tile.fragments[j].position.z;
    std::uint32_t bits = std::bit_cast<std::uint32_t>(z);
    bits = std::isnan(z) ? ~0u : (bits >> 31 != 0 ? ~bits : bits | 0x80000000u);
    scratch.keys[j] = std::uint64_t(bits) << 32 | j;
  }
  // (Highway's sort; a Sorter owns a buffer: one per thread.)
  static thread_local const hwy::Sorter sorter;
  sorter(scratch.keys.data(), n, hwy::SortAscending());
  scratch.order.resize(n);
  for (std::size_t k = 0; k < n; ++k) scratch.order[k] = std::uint32_t(scratch.keys[k]);
  scratch.sorted.resize(n);
  scratch.receivers.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    scratch.sorted[k] = tile.fragments[scratch.order[k]];
    scratch.receivers[k] = samples.samples[tile.pixels[scratch.order[k]]].receiver;
  }
  scratch.fragments.assign(scratch.sorted, scratch.receivers);
  scratch.masks.assign(n, raster.empty_disk());
  scratch.rasterized.assign(n, 0);
  // Each candidate set up for every fragment in lanes, and cleared from the mask of each fragment
  // that accepts it, with the rows in lanes. The masks are ANDs of per-triangle masks, so neither
  // the order nor the reference's batches of softtile_tile_triangle_limit candidates change them.
  const std::vector<std::uint32_t>& candidates = tile.candidates;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    // The candidates are scattered over the gathered triangles: fetch ahead.
    if (k + 8 < candidates.size()) __builtin_prefetch(&gathered.triangles[candidates[k + 8]]);
    const ref::GatheredTriangle& t = gathered.triangles[candidates[k]];
    out.tests += occlude_fragments(scratch.fragments, t.light_space, t.triangle, raster,
                                   scratch.masks.data(), scratch.rasterized.data());
  }
  out.masks.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.masks[scratch.order[k]] = scratch.masks[k];
  for (const std::uint64_t triangles : scratch.rasterized) {
    out.rasterized += triangles;
    out.rasterized_max = std::max(out.rasterized_max, triangles);
  }
}

}  // namespace softtile

namespace {

namespace ref = shadowcts::softtile;

class SimdSofttile final : public VariantTableAlgorithm<ref::Variant> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& row) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const ref::Variant& variant = row.config;
    check_receivers(c, samples);
    PhaseClock clock;
    AlgorithmOutput output;
    output.visible_fraction.assign(samples.samples.size(), 1.0f);
    ref::Gathered gathered;
    softtile::GatheredCones cones;
    run_with_thread_limit(c.parameters.threads, [&] {
      gathered = softtile::gather(c, samples);
      cones = softtile::gathered_cones(gathered);
    });
    clock.lap(build_phase);
    const softtile::DiskRaster raster(variant);
    const float inverse_scale = ref::disk_inverse_scale(gathered, variant);
    const std::size_t tiles =
        std::size_t(ref::tiles_across(samples.width)) * ref::tiles_across(samples.height);
    std::vector<ref::TileCounters> tile_counters(tiles);

    phase_progress::begin(tiles, "screen tiles");
    run_with_thread_limit(c.parameters.threads, [&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, tiles), [&](const tbb::blocked_range<std::size_t>& r) {
            ref::Tile tile;
            softtile::TileScratch scratch;
            softtile::TileRaster result;
            for (std::size_t index = r.begin(); index != r.end(); ++index) {
              if (!ref::prepare_tile_pixels(c, samples, gathered, variant, inverse_scale, index,
                                            tile))
                continue;
              softtile::cull_candidates(cones, tile.bound, tile.candidates);
              ref::TileCounters& counters = tile_counters[index];
              counters.relevant = true;
              counters.capsule = tile.bound.capsule;
              counters.candidates = tile.candidates.size();
              softtile::rasterize_tile(samples, gathered, raster, tile, scratch, result);
              counters.tests = result.tests;
              counters.rasterized = result.rasterized;
              counters.rasterized_max = result.rasterized_max;
              for (std::size_t j = 0; j < tile.pixels.size(); ++j)
                output.visible_fraction[tile.pixels[j]] =
                    float(result.masks[j].lit_cells()) / float(raster.disk_cells());
            }
            phase_progress::advance(r.size());
          });
    });
    clock.lap(query_phase);
    output.phase_ms = clock.times();

    output.counters = ref::to_counters(gathered, tile_counters);
    return output;
  }
};

}  // namespace
}  // namespace shadowcts::simd

namespace shadowcts {

std::unique_ptr<Algorithm> make_simd_softtile() {
  return std::make_unique<simd::SimdSofttile>(
      AlgorithmDescription{
          .id = "softtile",
          .backend = "simd",
          .summary = "softtile over oneTBB tiles with the disk bitmask rasterized in Highway lanes "
                     "(rows in lanes, one triangle's edge functions per vector)",
          .capabilities = {.output = OutputKind::soft_shadow, .sun_disk = true},
          // The variants of issue 21 (the others run too, and are tested, but each registered
          // variant is a conformance record whose exact soft oracle costs ~10 s of CI time).
          .registered = {"grid16", "grid16+rot", "rows15", "rows31", "post"}},
      softtile_variants());
}

}  // namespace shadowcts
