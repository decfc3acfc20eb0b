#include "gpu/softtile/softtile_algorithm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "reference/softtile/counters.h"
#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/softtile/softtile_tile.h"
#include "shadowcts/geometry/disk_reach.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

namespace ref = shadowcts::softtile;

static_assert(ref::cluster_size <= 64, "a cluster's surviving triangles are one 64-bit mask");
static_assert(ref::DiskBitmask::max_rows == softtile_kernel_max_rows);
static_assert(softtile_tile_size == 16, "the kernel's blocks are 16 x 16 pixels");

// The variants of issue 21 (each registered variant is a conformance record whose exact soft
// oracle costs CI time).
const std::vector<std::string>& kernel_variants() {
  static const std::vector<std::string> names{"grid16", "grid16+rot", "rows15", "rows31", "post"};
  return names;
}

SofttileCone kernel_cone(const ref::ShadowCone& cone) {
  SofttileCone k{};
  for (int i = 0; i < 3; ++i) k.tip[i] = cone.tip[i];
  k.start_height = cone.start_height;
  k.tip_length = glm::length(cone.tip);
  return k;
}

// The gathered clusters and triangles, the sun and the variant's disk.
void add_gathered(const ref::Gathered& gathered, const ref::Variant& variant,
                  SofttileKernelInput& input) {
  input.clusters.clear();
  input.triangle_cones.clear();
  input.triangles.clear();
  for (const ref::GatheredCluster& cluster : gathered.clusters)
    input.clusters.push_back({kernel_cone(cluster.cone), cluster.first, cluster.count});
  for (const ref::GatheredTriangle& t : gathered.triangles) {
    input.triangle_cones.push_back(kernel_cone(t.cone));
    SofttileTriangle k{};
    for (int v = 0; v < 3; ++v)
      for (int i = 0; i < 3; ++i) k.vertices[3 * v + i] = t.light_space[v][i];
    k.triangle = t.triangle;
    input.triangles.push_back(k);
  }
  for (int i = 0; i < 3; ++i) {
    input.sun.direction[i] = gathered.sun.direction[i];
    input.sun.axis[i] = -gathered.sun.direction[i];
  }
  // As distance_to_cone takes them from the cone's half-angle.
  input.sun.cos_radius = std::cos(gathered.sun.angular_radius);
  input.sun.sin_radius = std::sin(gathered.sun.angular_radius);

  const ref::DiskBitmask disk(variant);
  SofttileRaster& raster = input.raster;
  raster = SofttileRaster{};
  raster.rows = disk.rows();
  raster.columns = disk.columns();
  raster.full_row = disk.columns() == 32 ? 0xffffffffu : (1u << disk.columns()) - 1u;
  raster.half_columns = 0.5f * float(disk.columns());
  for (int r = 0; r < disk.rows(); ++r) {
    // DiskBitmask::clear_triangle's scanline centre.
    raster.y[r] = -1.0f + (float(r) + 0.5f) * 2.0f / float(disk.rows());
    raster.empty[r] = disk.row(r);
  }
  raster.disk_cells = std::uint32_t(disk.disk_cells());
  raster.inverse_scale = ref::disk_inverse_scale(gathered, variant);
  raster.reach_per_height = disk_reach_per_height(raster.inverse_scale);
  input.batch_capacity = std::uint32_t(softtile_tile_triangle_limit);
}

// Per pixel: the sample, the grid's rotation there (prepare_tile_pixels' angle, cos and sin) and
// its receiver; the camera and light space for the kernel's tile bounds and fragment setups.
void add_pixels(const Case& c, const ViewSamples& samples, const ref::Gathered& gathered,
                const ref::Variant& variant, SofttileKernelInput& input) {
  input.width = samples.width;
  input.height = samples.height;
  input.tiles_x = ref::tiles_across(samples.width);
  input.tiles_y = ref::tiles_across(samples.height);
  if (samples.samples.size() != std::size_t(samples.width) * samples.height)
    throw std::invalid_argument("softtile: the view samples are not width x height");
  for (int k = 0; k < 3; ++k) {
    input.eye[k] = double(c.camera.position[k]);
    input.light_axes[0][k] = gathered.light_space.x_axis[k];
    input.light_axes[1][k] = gathered.light_space.y_axis[k];
    input.light_axes[2][k] = gathered.light_space.z_axis[k];
  }
  input.fragments.assign(samples.samples.size(), SofttileFragment{});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const ViewSample& s = samples.samples[i];
                        if (s.sample_class != SampleClass::regular) continue;
                        SofttileFragment& f = input.fragments[i];
                        for (int k = 0; k < 3; ++k) f.world[k] = s.position[k];
                        f.cos_rotation = 1.0f;
                        f.sin_rotation = 0.0f;
                        if (variant.rotate) {
                          const double angle =
                              ref::rotation_angle(c.parameters.seed, s.pixel_x, s.pixel_y);
                          f.cos_rotation = float(std::cos(angle));
                          f.sin_rotation = float(std::sin(angle));
                        }
                        f.receiver = s.receiver;
                        f.relevant = 1;
                      }
                    });
}

// The reference's per-tile counts from the kernel's per-tile lists and per-pixel counts.
std::vector<ref::TileCounters> tile_counters(const ViewSamples& samples,
                                             const SofttileKernelResult& result) {
  std::vector<ref::TileCounters> tiles(result.tile_kinds.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    tiles[t].relevant = result.tile_kinds[t] != softtile_tile_empty;
    tiles[t].capsule = result.tile_kinds[t] == softtile_tile_capsule;
    tiles[t].candidates = tiles[t].relevant ? result.candidates[t] : 0;
  }
  const std::uint32_t tiles_x = ref::tiles_across(samples.width);
  for (std::size_t pixel = 0; pixel < result.tests.size(); ++pixel) {
    const std::size_t x = pixel % samples.width, y = pixel / samples.width;
    ref::TileCounters& tile = tiles[y / softtile_tile_size * tiles_x + x / softtile_tile_size];
    tile.tests += result.tests[pixel];
    tile.rasterized += result.rasterized[pixel];
    tile.rasterized_max = std::max<std::uint64_t>(tile.rasterized_max, result.rasterized[pixel]);
  }
  return tiles;
}

class SofttileKernelAlgorithm final : public VariantTableAlgorithm<ref::Variant> {
 public:
  explicit SofttileKernelAlgorithm(SofttileKernelBackend backend)
      : VariantTableAlgorithm(
            backend.describe("softtile",
                             Capabilities{.output = OutputKind::soft_shadow, .sun_disk = true}),
            select_variants(softtile_variants(), kernel_variants())),
        backend_(std::move(backend)) {}

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& row) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const ref::Variant& variant = row.config;
    check_receivers(c, samples);
    PhaseClock clock;
    AlgorithmOutput output;
    SofttileKernelInput input;
    SofttileKernelResult result;
    // The gather pass, the tile setup and the emulator's blocks keep to the case's thread limit.
    run_with_thread_limit(c.parameters.threads, [&] {
      const ref::Gathered gathered = ref::gather(c, samples);
      add_gathered(gathered, variant, input);
      clock.lap(build_phase);
      add_pixels(c, samples, gathered, variant, input);
      result = backend_.run_kernel(std::move(input));  // frees each array once uploaded
      clock.lap(query_phase);
      output.counters = ref::to_counters(gathered, tile_counters(samples, result));
    });
    output.phase_ms = clock.times();
    output.visible_fraction = std::move(result.visible_fraction);
    // A block of 256 threads per tile (a tile without relevant pixels exits at once).
    if (backend_.emulated)
      output.counters.push_back(
          {"emulated_threads", 256 * std::uint64_t(result.tile_kinds.size())});
    return output;
  }

  SofttileKernelBackend backend_;
};

}  // namespace

SofttileKernelInput softtile_kernel_input(const Case& c, const ViewSamples& samples,
                                          const softtile::Variant& variant,
                                          const softtile::Gathered& gathered) {
  SofttileKernelInput input;
  add_gathered(gathered, variant, input);
  add_pixels(c, samples, gathered, variant, input);
  return input;
}

std::unique_ptr<Algorithm> make_softtile_kernel_algorithm(SofttileKernelBackend backend) {
  return std::make_unique<SofttileKernelAlgorithm>(std::move(backend));
}

std::unique_ptr<Algorithm> make_softtile_cuda_emu() {
  SofttileKernelBackend backend;
  backend.backend = "cuda-emu";
  backend.summary =
      "the cuda backend's softtile kernel EMULATED on the host (gpu/emulator: a fiber per CUDA "
      "thread, no GPU involved): block per tile, shared candidate list, thread per pixel bitmask";
  backend.run_kernel = run_softtile_kernel_emulated;
  backend.emulated = true;
  return make_softtile_kernel_algorithm(std::move(backend));
}

}  // namespace shadowcts
