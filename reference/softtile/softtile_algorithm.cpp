#include "reference/softtile/softtile_algorithm.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "oracles/hard_shadow_inputs.h"
#include "oracles/thread_limit.h"
#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/softtile_gather.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/phase_clock.h"

namespace shadowcts {
namespace {

using namespace softtile;

struct TileCounters {
  std::uint64_t relevant = 0, capsule = 0, candidates = 0, overflow_batches = 0, tests = 0,
                rasterized = 0, rasterized_max = 0;
};

// The bound of a tile's relevant samples. The samples lie in the tile's slice of the view frustum
// between its min and max depth; seen from the eye along the tile's mean direction c, a sample at
// distance t along c lies within k t of the axis (k the largest ratio over the tile). A tapered
// capsule from t_min to t_max with radii k t_min, k t_max contains them all; when the depth range
// is short against the radius, one sphere around them is tighter and is used instead.
TileBound tile_bound(const glm::dvec3& eye, const std::vector<glm::dvec3>& positions) {
  glm::dvec3 direction(0.0), lo(positions[0]), hi(positions[0]);
  for (const glm::dvec3& p : positions) {
    direction += glm::normalize(p - eye);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double scale = glm::length(eye) + std::max(glm::length(lo), glm::length(hi));
  const double margin = 1e-6 * scale;
  TileBound sphere;
  sphere.a = 0.5 * (lo + hi);
  for (const glm::dvec3& p : positions)
    sphere.radius_a = std::max(sphere.radius_a, glm::length(p - sphere.a));
  sphere.radius_a = sphere.radius_a * (1.0 + 1e-9) + margin;
  if (positions.size() == 1 || !(glm::length(direction) > 0.0)) return sphere;
  direction = glm::normalize(direction);
  double t_min = std::numeric_limits<double>::max(), t_max = 0.0, k = 0.0;
  for (const glm::dvec3& p : positions) {
    const double t = glm::dot(p - eye, direction);
    if (!(t > 0.0)) return sphere;
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
    k = std::max(k, glm::length(p - eye - t * direction) / t);
  }
  TileBound capsule;
  capsule.capsule = true;
  capsule.a = eye + t_min * direction;
  capsule.b = eye + t_max * direction;
  capsule.radius_a = k * t_min * (1.0 + 1e-9) + margin;
  capsule.radius_b = k * t_max * (1.0 + 1e-9) + margin;
  return t_max - t_min > 2.0 * capsule.radius_b ? capsule : sphere;
}

// A per-pixel rotation angle in [0, 2 pi): a hash of the seed and the pixel, so every run and
// every thread count gives the same grid.
double rotation_angle(std::uint64_t seed, std::uint32_t x, std::uint32_t y) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull ^ (std::uint64_t(x) << 32 | y);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return 2.0 * std::numbers::pi * double(z >> 11) * 0x1p-53;
}

class Softtile final : public Algorithm {
 public:
  Softtile() {
    info_.id = "softtile";
    info_.backend = "reference";
    info_.variants = variant_names();
    info_.summary =
        "tiled per-triangle soft shadow volumes (Kalbertodt 2023): gather pass, 16x16 tiles with "
        "sphere/capsule bounds and truncated cones, per-pixel disk bitmask rasterization";
    info_.capabilities.output = OutputKind::soft_shadow;
    info_.capabilities.sun_disk = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  // build: the gather pass (clusters, triangle cones, light-space triangles); query: the tile and
  // fragment pass (tile bounds, cone culling, per-pixel disk rasterization).
  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  SoftErrorBudget soft_error_budget(const std::string& variant) const override {
    return softtile_error_budget(variant);
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant_name) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const Variant variant = parse_variant(variant_name);
    check_receivers(c, samples);
    PhaseClock clock;
    AlgorithmOutput output;
    output.visible_fraction.assign(samples.samples.size(), 1.0f);
    const Gathered gathered = gather(c, samples);
    clock.lap(build_phase);
    const DiskBitmask empty_disk(variant);
    const float inverse_scale =
        float(1.0 / (variant.sine_normalization ? std::sin(gathered.sun.angular_radius)
                                                : std::tan(gathered.sun.angular_radius)));
    const glm::dvec3 eye(c.camera.position);

    const std::uint32_t tiles_x = (samples.width + softtile_tile_size - 1) / softtile_tile_size;
    const std::uint32_t tiles_y = (samples.height + softtile_tile_size - 1) / softtile_tile_size;
    std::vector<TileCounters> tile_counters(std::size_t(tiles_x) * tiles_y);

    run_with_thread_limit(c.parameters.threads, [&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, tile_counters.size()),
          [&](const tbb::blocked_range<std::size_t>& range) {
            std::vector<std::size_t> pixels;
            std::vector<glm::dvec3> positions;
            std::vector<std::uint32_t> candidates;
            std::vector<DiskBitmask> masks;
            std::vector<std::uint64_t> rasterized_per_pixel;
            for (std::size_t tile = range.begin(); tile != range.end(); ++tile) {
              TileCounters& counters = tile_counters[tile];
              const std::uint32_t x0 = std::uint32_t(tile % tiles_x) * softtile_tile_size;
              const std::uint32_t y0 = std::uint32_t(tile / tiles_x) * softtile_tile_size;
              // Relevant pixels: regular samples (facing the light, not sky).
              pixels.clear();
              positions.clear();
              for (std::uint32_t y = y0; y < std::min(y0 + softtile_tile_size, samples.height); ++y)
                for (std::uint32_t x = x0; x < std::min(x0 + softtile_tile_size, samples.width);
                     ++x) {
                  const std::size_t i = std::size_t(y) * samples.width + x;
                  if (samples.samples[i].sample_class != SampleClass::regular) continue;
                  pixels.push_back(i);
                  positions.emplace_back(samples.samples[i].position);
                }
              if (pixels.empty()) continue;  // early exit
              counters.relevant = 1;
              const TileBound bound = tile_bound(eye, positions);
              counters.capsule = bound.capsule ? 1 : 0;
              // Cull cluster cones, then the cones of the surviving clusters' triangles.
              candidates.clear();
              for (const GatheredCluster& cluster : gathered.clusters) {
                if (!may_shadow(gathered.sun, cluster.cone, bound)) continue;
                for (std::uint32_t k = cluster.first; k < cluster.first + cluster.count; ++k)
                  if (may_shadow(gathered.sun, gathered.triangles[k].cone, bound))
                    candidates.push_back(k);
              }
              counters.candidates = candidates.size();
              masks.assign(pixels.size(), empty_disk);
              rasterized_per_pixel.assign(pixels.size(), 0);
              std::vector<FragmentSetup> fragments(pixels.size());
              for (std::size_t j = 0; j < pixels.size(); ++j) {
                const ViewSample& s = samples.samples[pixels[j]];
                fragments[j].position = gathered.light_space.to_light(s.position);
                fragments[j].inverse_scale = inverse_scale;
                if (variant.rotate) {
                  const double angle = rotation_angle(c.parameters.seed, s.pixel_x, s.pixel_y);
                  fragments[j].cos_rotation = float(std::cos(angle));
                  fragments[j].sin_rotation = float(std::sin(angle));
                }
              }
              // The shared-memory buffer holds softtile_tile_triangle_limit triangles: a longer
              // list is rasterized in several batches (the bitmasks persist), never truncated.
              for (std::size_t begin = 0; begin < candidates.size();
                   begin += softtile_tile_triangle_limit) {
                if (begin > 0) ++counters.overflow_batches;
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
          });
    });
    clock.lap(query_phase);
    output.phase_ms = clock.times();

    // Sums and maxima of per-tile integers: independent of the partitioning.
    TileCounters total;
    std::uint64_t candidates_max = 0, overflowing = 0;
    for (const TileCounters& t : tile_counters) {
      total.relevant += t.relevant;
      total.capsule += t.capsule;
      total.candidates += t.candidates;
      total.overflow_batches += t.overflow_batches;
      total.tests += t.tests;
      total.rasterized += t.rasterized;
      total.rasterized_max = std::max(total.rasterized_max, t.rasterized_max);
      candidates_max = std::max(candidates_max, t.candidates);
      overflowing += t.candidates > softtile_tile_triangle_limit ? 1 : 0;
    }
    output.counters = {{"gather_clusters", gathered.clusters_in},
                       {"gather_clusters_culled", gathered.clusters_culled},
                       {"gather_triangles", gathered.triangles.size()},
                       {"gather_light_facing_dropped", gathered.light_facing_dropped},
                       {"tiles", tile_counters.size()},
                       {"tiles_with_relevant_pixels", total.relevant},
                       {"tile_capsule_bounds", total.capsule},
                       {"tile_candidates_total", total.candidates},
                       {"tile_candidates_max", candidates_max},
                       {"overflowing_tiles", overflowing},
                       {"overflow_batches", total.overflow_batches},
                       {"pixel_triangle_tests", total.tests},
                       {"triangles_rasterized", total.rasterized},
                       {"triangles_rasterized_max_per_pixel", total.rasterized_max}};
    return output;
  }

 private:
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_softtile() {
  return std::make_unique<Softtile>();
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
