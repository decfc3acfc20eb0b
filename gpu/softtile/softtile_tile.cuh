#pragma once
// The softtile eval pass, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda`
// backend, the host compiler into `cuda-emu` against the emulator. One block per 16 x 16 pixel
// tile, one thread per pixel:
//  - setup: one thread builds the tile's bound (sphere or tapered capsule) from its relevant
//    samples in the reference's order; each thread moves its sample into light space;
//  - culling: each thread takes one cluster of the gathered list, tests its cone against the
//    tile's bound and then its triangles' cones (at most 64, a bit each); a block scan of the
//    survivors' counts places them in the tile's candidate list in shared memory in gathered order,
//    exactly the reference's cull_candidates list;
//  - rasterization: a full list (batch_capacity triangles, the post's shared buffer) or the last
//    part is staged through shared memory a block's width at a time, and every thread clears each
//    candidate from its own disk bitmask held in registers.
// The float and double operations are the reference's in its order, rounded one at a time (no
// FMA under nvcc): the candidate lists and bitmasks are the reference's bit for bit.
#include <bit>
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "gpu/softtile/disk_bitmask.cuh"
#include "gpu/softtile/fragment_occlusion.cuh"
#include "gpu/softtile/shadow_cone.cuh"
#include "gpu/softtile/softtile_kernel.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace softtile {

constexpr int tile_size = 16;
constexpr int threads_per_block = tile_size * tile_size;  // a thread per pixel
constexpr int warps_per_block = threads_per_block / 32;
// The reference's softtile_tile_triangle_limit: the shared candidate buffer.
constexpr std::uint32_t max_batch_capacity = 2048;

struct KernelParams {
  std::uint32_t width, height, tiles_x;
  const SofttileFragment* fragments;
  double eye[3];
  double light_axes[3][3];
  const SofttileCluster* clusters;
  std::uint32_t cluster_count;
  const SofttileCone* triangle_cones;
  const SofttileTriangle* triangles;
  SofttileSun sun;
  SofttileRaster raster;
  std::uint32_t batch_capacity;
  float* visible_fraction;
  std::uint32_t* tests;
  std::uint32_t* rasterized;
  std::uint32_t* tile_candidates;
  std::uint8_t* tile_kinds;
  // Optional (null): each tile's list (tile t's from t * triangle_count on), the per-pixel masks.
  std::uint32_t* candidate_list;
  std::uint32_t triangle_count;
  std::uint32_t* masks;
  unsigned long long* blocks_started;  // the launch's progress (gpu/kernel_progress.cuh)
};

__device__ inline int bit_count64(std::uint64_t x) {
#if SHADOWCTS_EMULATED
  return std::popcount(x);
#else
  return __popcll(x);
#endif
}

__device__ inline int lowest_bit(std::uint64_t x) {
#if SHADOWCTS_EMULATED
  return std::countr_zero(x);
#else
  return __ffsll(static_cast<long long>(x)) - 1;
#endif
}

// The exclusive prefix sum of `value` over the block in thread order, and the block's total.
// Every thread of the block must call it.
__device__ inline std::uint32_t block_exclusive_scan(std::uint32_t value, std::uint32_t& total) {
  SHADOWCTS_SHARED(std::uint32_t[warps_per_block], warp_totals);
  const unsigned lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  std::uint32_t inclusive = value;
  for (unsigned delta = 1; delta < 32; delta *= 2) {
    const std::uint32_t below = __shfl_up_sync(0xffffffffu, inclusive, delta);
    if (lane >= delta) inclusive += below;
  }
  if (lane == 31) warp_totals[warp] = inclusive;
  __syncthreads();
  std::uint32_t before = 0;
  total = 0;
  for (unsigned w = 0; w < warps_per_block; ++w) {
    const std::uint32_t t = warp_totals[w];
    if (w < warp) before += t;
    total += t;
  }
  __syncthreads();  // the next scan overwrites warp_totals
  return before + inclusive - value;
}

// Bit k set: triangle cluster.first + k of the cluster is a candidate of the tile (the cluster's
// cone and then the triangle's may shadow the bound).
__device__ inline std::uint64_t cull_cluster(const KernelParams& p, std::uint32_t index,
                                             const SofttileBound& bound) {
  const SofttileCluster cluster = p.clusters[index];
  if (!may_shadow(p.sun, cluster.cone, bound)) return 0;
  std::uint64_t survivors = 0;
  for (std::uint32_t k = 0; k < cluster.count; ++k)
    if (may_shadow(p.sun, p.triangle_cones[cluster.first + k], bound))
      survivors |= std::uint64_t{1} << k;
  return survivors;
}

// glm::normalize: v * (1 / sqrt(dot(v, v))).
__device__ inline void normalize3(double v[3]) {
  const double inverse = 1.0 / length3(v);
  for (int k = 0; k < 3; ++k) v[k] = rounded_mul(v[k], inverse);
}

// The sample of pixel (x, y) in double, and whether it is a relevant one.
__device__ inline bool tile_sample(const KernelParams& p, std::uint32_t x, std::uint32_t y,
                                   double position[3]) {
  const SofttileFragment f = p.fragments[std::size_t(y) * p.width + x];
  for (int k = 0; k < 3; ++k) position[k] = f.world[k];
  return f.relevant != 0;
}

// The reference's tile_bound (softtile_tile.cpp) of the tile's relevant samples, visited in its
// order (rows, then columns): the sums and maxima are order-dependent in floating point, so one
// thread builds it. Then may_shadow's terms of it.
__device__ inline SofttileBound build_tile_bound(const KernelParams& p, std::uint32_t x0,
                                                 std::uint32_t y0) {
  const std::uint32_t x1 = x0 + tile_size < p.width ? x0 + tile_size : p.width;
  const std::uint32_t y1 = y0 + tile_size < p.height ? y0 + tile_size : p.height;
  double direction[3] = {0.0, 0.0, 0.0}, lo[3] = {}, hi[3] = {}, position[3], v[3];
  std::uint32_t count = 0;
  for (std::uint32_t y = y0; y < y1; ++y)
    for (std::uint32_t x = x0; x < x1; ++x) {
      if (!tile_sample(p, x, y, position)) continue;
      for (int k = 0; k < 3; ++k) v[k] = rounded_sub(position[k], p.eye[k]);
      normalize3(v);
      for (int k = 0; k < 3; ++k) {
        direction[k] = rounded_add(direction[k], v[k]);
        lo[k] = count == 0 ? position[k] : std_min(lo[k], position[k]);
        hi[k] = count == 0 ? position[k] : std_max(hi[k], position[k]);
      }
      ++count;
    }
  const double scale = rounded_add(length3(p.eye), std_max(length3(lo), length3(hi)));
  const double margin = rounded_mul(1e-6, scale);
  SofttileBound bound{};
  for (int k = 0; k < 3; ++k) bound.a[k] = rounded_mul(0.5, rounded_add(lo[k], hi[k]));
  double radius = 0.0;
  for (std::uint32_t y = y0; y < y1; ++y)
    for (std::uint32_t x = x0; x < x1; ++x) {
      if (!tile_sample(p, x, y, position)) continue;
      for (int k = 0; k < 3; ++k) v[k] = rounded_sub(position[k], bound.a[k]);
      radius = std_max(radius, length3(v));
    }
  bound.radius_a = rounded_add(rounded_mul(radius, 1.0 + 1e-9), margin);
  bool capsule = count > 1 && length3(direction) > 0.0;
  if (capsule) {
    normalize3(direction);
    double t_min = DBL_MAX, t_max = 0.0, k_max = 0.0;
    for (std::uint32_t y = y0; y < y1 && capsule; ++y)
      for (std::uint32_t x = x0; x < x1; ++x) {
        if (!tile_sample(p, x, y, position)) continue;
        for (int k = 0; k < 3; ++k) v[k] = rounded_sub(position[k], p.eye[k]);
        const double t = dot3(v, direction);
        if (!(t > 0.0)) {  // the reference returns the sphere
          capsule = false;
          break;
        }
        t_min = std_min(t_min, t);
        t_max = std_max(t_max, t);
        for (int k = 0; k < 3; ++k) v[k] = rounded_sub(v[k], rounded_mul(t, direction[k]));
        k_max = std_max(k_max, length3(v) / t);
      }
    if (capsule) {
      const double radius_b =
          rounded_add(rounded_mul(rounded_mul(k_max, t_max), 1.0 + 1e-9), margin);
      capsule = rounded_sub(t_max, t_min) > rounded_mul(2.0, radius_b);
      if (capsule) {
        for (int k = 0; k < 3; ++k) {
          bound.a[k] = rounded_add(p.eye[k], rounded_mul(t_min, direction[k]));
          bound.b[k] = rounded_add(p.eye[k], rounded_mul(t_max, direction[k]));
        }
        bound.radius_a = rounded_add(rounded_mul(rounded_mul(k_max, t_min), 1.0 + 1e-9), margin);
        bound.radius_b = radius_b;
      }
    }
  }
  bound.capsule = capsule ? 1u : 0u;
  // may_shadow's terms of the bound, as the reference computes them in may_shadow.
  double ab[3];
  for (int k = 0; k < 3; ++k) {
    bound.middle[k] = rounded_mul(0.5, rounded_add(bound.a[k], bound.b[k]));
    ab[k] = rounded_sub(bound.b[k], bound.a[k]);
    bound.ab[k] = ab[k];
  }
  bound.length_a = length3(bound.a);
  bound.length_b = length3(bound.b);
  bound.enclosing =
      rounded_add(rounded_mul(0.5, length3(ab)), std_max(bound.radius_a, bound.radius_b));
  bound.dr = rounded_sub(bound.radius_b, bound.radius_a);
  bound.lipschitz = rounded_add(length3(ab), absolute(bound.dr));
  return bound;
}

// LightSpace::to_light: dot products in double, rounded to float.
__device__ inline FragmentSetup fragment_setup(const KernelParams& p, const SofttileFragment& f) {
  FragmentSetup setup;
  const double world[3] = {f.world[0], f.world[1], f.world[2]};
  for (int k = 0; k < 3; ++k) setup.position[k] = float(dot3(world, p.light_axes[k]));
  setup.cos_rotation = f.cos_rotation;
  setup.sin_rotation = f.sin_rotation;
  return setup;
}

#if SHADOWCTS_EMULATED
#define SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS
#else
#define SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS __launch_bounds__(threads_per_block)
#endif

__global__ void SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS softtile_tiles(KernelParams p) {
  count_started_block(p.blocks_started);
  SHADOWCTS_SHARED(std::uint32_t[max_batch_capacity], list);  // the tile's candidates
  SHADOWCTS_SHARED(SofttileTriangle[threads_per_block], staged);
  SHADOWCTS_SHARED(SofttileBound, shared_bound);

  const std::uint32_t tile = blockIdx.x;
  const std::uint32_t x0 = (tile % p.tiles_x) * tile_size, y0 = (tile / p.tiles_x) * tile_size;
  const std::uint32_t x = x0 + threadIdx.x % tile_size, y = y0 + threadIdx.x / tile_size;
  const std::size_t pixel = std::size_t(y) * p.width + x;
  SofttileFragment sample{};
  bool has_pixel = x < p.width && y < p.height;
  if (has_pixel) {
    sample = p.fragments[pixel];
    has_pixel = sample.relevant != 0;
  }
  if (!__syncthreads_or(has_pixel)) {  // the whole block: no pixel (the reference's early exit)
    if (threadIdx.x == 0) {
      p.tile_candidates[tile] = 0;
      p.tile_kinds[tile] = softtile_tile_empty;
    }
    return;
  }
  if (threadIdx.x == 0) {
    const SofttileBound built = build_tile_bound(p, x0, y0);
    shared_bound = built;
    p.tile_kinds[tile] = built.capsule ? softtile_tile_capsule : softtile_tile_sphere;
  }
  const FragmentSetup fragment = fragment_setup(p, sample);
  __syncthreads();
  const SofttileBound bound = shared_bound;
  const int rows = p.raster.rows;
  std::uint32_t mask[softtile_kernel_max_rows];
  for (int r = 0; r < rows; ++r) mask[r] = p.raster.empty[r];
  std::uint32_t tests = 0, rasterized = 0;

  // Rasterizes list[0, count) into every pixel's mask.
  const auto rasterize = [&](std::uint32_t count) {
    for (std::uint32_t begin = 0; begin < count; begin += threads_per_block) {
      __syncthreads();  // the list is written; the previous stage is read by every thread
      if (begin + threadIdx.x < count) staged[threadIdx.x] = p.triangles[list[begin + threadIdx.x]];
      __syncthreads();
      if (!has_pixel) continue;
      const std::uint32_t end =
          count - begin < std::uint32_t(threads_per_block) ? count - begin : threads_per_block;
      for (std::uint32_t i = 0; i < end; ++i) {
        const SofttileTriangle triangle = staged[i];  // every lane reads one slot: a broadcast
        if (triangle.triangle == sample.receiver) continue;
        ++tests;
        float edges[9];
        if (!triangle_edges(fragment, p.raster.inverse_scale, p.raster.reach_per_height, triangle,
                            edges))
          continue;
        clear_triangle(p.raster, edges, mask);
        ++rasterized;
      }
    }
  };

  // The list so far (block-uniform) and the tile's candidates before this chunk of clusters.
  std::uint32_t filled = 0, total = 0;
  for (std::uint32_t chunk = 0; chunk < p.cluster_count; chunk += threads_per_block) {
    const std::uint32_t cluster = chunk + threadIdx.x;
    std::uint64_t survivors = 0;
    std::uint32_t first = 0;
    if (cluster < p.cluster_count) {
      survivors = cull_cluster(p, cluster, bound);
      first = p.clusters[cluster].first;
    }
    std::uint32_t chunk_total = 0;
    const std::uint32_t offset =
        block_exclusive_scan(std::uint32_t(bit_count64(survivors)), chunk_total);
    if (p.candidate_list) {
      std::size_t at = std::size_t(tile) * p.triangle_count + total + offset;
      for (std::uint64_t bits = survivors; bits != 0; bits &= bits - 1)
        p.candidate_list[at++] = first + std::uint32_t(lowest_bit(bits));
    }
    // Survivors at chunk positions [consumed, consumed + space) fill the rest of the list; a full
    // list is rasterized and emptied.
    for (std::uint32_t consumed = 0; consumed < chunk_total;) {
      const std::uint32_t space = p.batch_capacity - filled;
      std::uint32_t position = offset;
      for (std::uint64_t bits = survivors; bits != 0; bits &= bits - 1, ++position)
        if (position >= consumed && position - consumed < space)
          list[filled + position - consumed] = first + std::uint32_t(lowest_bit(bits));
      const std::uint32_t taken = chunk_total - consumed < space ? chunk_total - consumed : space;
      filled += taken;
      consumed += taken;
      if (filled == p.batch_capacity) {
        rasterize(filled);  // its barriers order the staging reads before the refill
        filled = 0;
      }
    }
    total += chunk_total;
  }
  rasterize(filled);

  if (threadIdx.x == 0) p.tile_candidates[tile] = total;
  if (!has_pixel) return;
  int lit = 0;
  for (int r = 0; r < rows; ++r) lit += bit_count(mask[r]);
  p.visible_fraction[pixel] = rounded_div(float(lit), float(p.raster.disk_cells));
  p.tests[pixel] = tests;
  p.rasterized[pixel] = rasterized;
  if (p.masks)
    for (int r = 0; r < softtile_kernel_max_rows; ++r)
      p.masks[pixel * softtile_kernel_max_rows + r] = r < rows ? mask[r] : 0u;
}

// Takes the input by value: each host array is freed once uploaded.
inline SofttileKernelResult run(SofttileKernelInput input) {
  const std::size_t pixels = std::size_t(input.width) * input.height;
  const std::size_t tiles = std::size_t(input.tiles_x) * input.tiles_y;
  if (input.fragments.size() != pixels ||
      input.tiles_x != (input.width + tile_size - 1) / tile_size ||
      input.tiles_y != (input.height + tile_size - 1) / tile_size ||
      input.triangle_cones.size() != input.triangles.size())
    throw std::invalid_argument("softtile kernel: inconsistent input sizes");
  if (input.batch_capacity == 0 || input.batch_capacity > max_batch_capacity)
    throw std::invalid_argument("softtile kernel: batch capacity outside 1.." +
                                std::to_string(max_batch_capacity));
  for (const SofttileCluster& c : input.clusters)
    if (c.count > 64 || std::size_t(c.first) + c.count > input.triangles.size())
      throw std::invalid_argument("softtile kernel: a cluster of more than 64 triangles");
  SofttileKernelResult result;
  result.visible_fraction.assign(pixels, 1.0f);
  result.tests.assign(pixels, 0);
  result.rasterized.assign(pixels, 0);
  result.candidates.assign(tiles, 0);
  result.tile_kinds.assign(tiles, softtile_tile_empty);
  if (pixels == 0) return result;

  const auto cluster_count = static_cast<std::uint32_t>(input.clusters.size());
  const std::size_t triangle_count = input.triangles.size();
  const DeviceArray<SofttileFragment> fragments = upload_and_free(input.fragments);
  const DeviceArray<SofttileCluster> clusters = upload_and_free(input.clusters);
  const DeviceArray<SofttileCone> cones = upload_and_free(input.triangle_cones);
  const DeviceArray<SofttileTriangle> triangles = upload_and_free(input.triangles);
  DeviceArray<float> visible(pixels);
  DeviceArray<std::uint32_t> tests(pixels), rasterized(pixels), candidates(tiles);
  DeviceArray<std::uint8_t> kinds(tiles);
  visible.upload(result.visible_fraction);
  tests.upload(result.tests);
  rasterized.upload(result.rasterized);

  KernelParams p{};
  p.width = input.width;
  p.height = input.height;
  p.tiles_x = input.tiles_x;
  p.fragments = fragments.data();
  for (int k = 0; k < 3; ++k) {
    p.eye[k] = input.eye[k];
    for (int j = 0; j < 3; ++j) p.light_axes[k][j] = input.light_axes[k][j];
  }
  p.clusters = clusters.data();
  p.cluster_count = cluster_count;
  p.triangle_cones = cones.data();
  p.triangles = triangles.data();
  p.sun = input.sun;
  p.raster = input.raster;
  p.batch_capacity = input.batch_capacity;
  p.visible_fraction = visible.data();
  p.tests = tests.data();
  p.rasterized = rasterized.data();
  p.tile_candidates = candidates.data();
  p.tile_kinds = kinds.data();
  const std::size_t mask_words = input.record_masks ? pixels * softtile_kernel_max_rows : 0;
  DeviceArray<std::uint32_t> masks(mask_words);
  masks.zero();  // pixels without a relevant sample keep zero rows
  p.masks = masks.data();
  // A list holds each gathered triangle at most once: room for all of them in every tile (the
  // tests' small frames only).
  p.triangle_count = static_cast<std::uint32_t>(triangle_count);
  DeviceArray<std::uint32_t> lists(input.record_candidates ? tiles * triangle_count : 0);
  p.candidate_list = input.record_candidates ? lists.data() : nullptr;
  KernelProgress progress;
  p.blocks_started = progress.counter();
  SHADOWCTS_LAUNCH(softtile_tiles, static_cast<unsigned>(tiles), threads_per_block, 0)(p);
  progress.wait("softtile_tiles", tiles);
  result.visible_fraction = visible.download();
  result.tests = tests.download();
  result.rasterized = rasterized.download();
  result.candidates = candidates.download();
  result.tile_kinds = kinds.download();
  result.masks = masks.download();
  if (input.record_candidates) {
    const std::vector<std::uint32_t> all = lists.download();
    result.candidate_offsets.assign(tiles + 1, 0);
    for (std::size_t t = 0; t < tiles; ++t) {
      result.candidate_offsets[t + 1] = result.candidate_offsets[t] + result.candidates[t];
      const auto first = all.begin() + std::ptrdiff_t(t * triangle_count);
      result.candidate_list.insert(result.candidate_list.end(), first,
                                   first + std::ptrdiff_t(result.candidates[t]));
    }
  }
  return result;
}

}  // namespace softtile
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
