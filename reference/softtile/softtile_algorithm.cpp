#include "reference/softtile/softtile_algorithm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/softtile/counters.h"
#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_tile.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

using namespace softtile;

static_assert(softtile_tile_size == tile_size);

class Softtile final : public VariantTableAlgorithm<softtile::Variant> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // build: the gather pass (clusters, triangle cones, light-space triangles); query: the tile and
  // fragment pass (tile bounds, cone culling, per-pixel disk rasterization).
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& row) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const softtile::Variant& variant = row.config;
    check_receivers(c, samples);
    PhaseClock clock;
    AlgorithmOutput output;
    output.visible_fraction.assign(samples.samples.size(), 1.0f);
    Gathered gathered;
    run_with_thread_limit(c.parameters.threads, [&] { gathered = gather(c, samples); });
    clock.lap(build_phase);
    const DiskBitmask empty_disk(variant);
    const float inverse_scale = disk_inverse_scale(gathered, variant);
    const std::uint32_t tiles_x = tiles_across(samples.width);
    const std::uint32_t tiles_y = tiles_across(samples.height);
    std::vector<TileCounters> tile_counters(std::size_t(tiles_x) * tiles_y);

    phase_progress::begin(tile_counters.size(), "screen tiles");
    run_with_thread_limit(c.parameters.threads, [&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, tile_counters.size()),
          [&](const tbb::blocked_range<std::size_t>& range) {
            Tile tile;
            std::vector<DiskBitmask> masks;
            std::vector<std::uint64_t> rasterized_per_pixel;
            for (std::size_t index = range.begin(); index != range.end(); ++index) {
              TileCounters& counters = tile_counters[index];
              if (!prepare_tile(c, samples, gathered, variant, inverse_scale, index, tile))
                continue;
              const std::vector<std::size_t>& pixels = tile.pixels;
              const std::vector<std::uint32_t>& candidates = tile.candidates;
              const std::vector<FragmentSetup>& fragments = tile.fragments;
              counters.relevant = true;
              counters.capsule = tile.bound.capsule;
              counters.candidates = candidates.size();
              masks.assign(pixels.size(), empty_disk);
              rasterized_per_pixel.assign(pixels.size(), 0);
              // The shared-memory buffer holds softtile_tile_triangle_limit triangles: a longer
              // list is rasterized in several batches (the bitmasks persist), never truncated.
              for (std::size_t begin = 0; begin < candidates.size();
                   begin += softtile_tile_triangle_limit) {
                const std::size_t end =
                    std::min(candidates.size(), begin + softtile_tile_triangle_limit);
                for (std::size_t j = 0; j < pixels.size(); ++j) {
                  const std::uint32_t receiver = samples.samples[pixels[j]].receiver;
                  std::array<glm::vec3, 3> edges;
                  for (std::size_t k = begin; k < end; ++k) {
                    const GatheredTriangle& t = gathered.triangles[candidates[k]];
                    if (t.triangle == receiver) continue;
                    ++counters.tests;
                    if (!triangle_edges(fragments[j], t.light_space, edges)) continue;
                    masks[j].clear_triangle(edges);
                    ++rasterized_per_pixel[j];
                  }
                }
              }
              for (std::size_t j = 0; j < pixels.size(); ++j) {
                output.visible_fraction[pixels[j]] =
                    float(masks[j].lit_cells()) / float(masks[j].disk_cells());
                counters.rasterized += rasterized_per_pixel[j];
                counters.rasterized_max =
                    std::max(counters.rasterized_max, rasterized_per_pixel[j]);
              }
            }
            phase_progress::advance(range.size());
          });
    });
    clock.lap(query_phase);
    output.phase_ms = clock.times();

    output.counters = to_counters(gathered, tile_counters);
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_softtile() {
  return std::make_unique<Softtile>(
      AlgorithmDescription{
          .id = "softtile",
          .backend = "reference",
          .summary = "tiled per-triangle soft shadow volumes (Kalbertodt 2023): gather pass, "
                     "16x16 tiles with sphere/capsule bounds and truncated cones, per-pixel disk "
                     "bitmask rasterization",
          .capabilities = {.output = OutputKind::soft_shadow, .sun_disk = true}},
      softtile_variants());
}

std::vector<AlgorithmVariant<Variant>> softtile_variants() {
  auto table = variant_table(variant_names(), parse_variant);
  for (auto& v : table) v.soft_error_budget = softtile_error_budget(v.name);
  return table;
}

SoftErrorBudget softtile_error_budget(const std::string& variant) {
  const Variant v = parse_variant(variant);
  const double cells = double(DiskBitmask(v).disk_cells());
  // docs/soft-shadow-budgets.md. Per sample: a straight edge passes through at most rows + columns
  // cells of the grid, and centre sampling misclassifies at most those. Mean: twice the expected
  // |e| of one edge whose crossings are uniformly placed, as if every sample were in a penumbra.
  SoftErrorBudget budget;
  budget.per_sample = double(v.rows + v.columns) / cells;
  budget.mean = 2.0 * std::sqrt(double(v.rows + v.columns) / 12.0) / cells;
  if (v.sine_normalization) {
    // The sin(a) disk misses the annulus between tangent radii sin(a) and tan(a): a share
    // sin^2(a) of the disk. Budgeted for a <= ~5.7 degrees (sin^2 a <= 0.01); larger disks fail,
    // which is what the shortcut costs.
    budget.per_sample += 0.01;
    budget.mean += 0.01;
  }
  return budget;
}

}  // namespace shadowcts
