#pragma once
// The softtile eval pass, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda`
// backend, the host compiler into `cuda-emu` against the emulator. One block per 16 x 16 pixel
// tile, one thread per pixel:
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
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/emulator/kernel.h"
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
  const SofttileBound* bounds;
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
  // Optional (null): each tile's list (tile t's from t * triangle_count on), the per-pixel masks.
  std::uint32_t* candidate_list;
  std::uint32_t triangle_count;
  std::uint32_t* masks;
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

#if SHADOWCTS_EMULATED
#define SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS
#else
#define SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS __launch_bounds__(threads_per_block)
#endif

__global__ void SHADOWCTS_SOFTTILE_LAUNCH_BOUNDS softtile_tiles(KernelParams p) {
  SHADOWCTS_SHARED(std::uint32_t[max_batch_capacity], list);  // the tile's candidates
  SHADOWCTS_SHARED(SofttileTriangle[threads_per_block], staged);

  const std::uint32_t tile = blockIdx.x;
  const SofttileBound bound = p.bounds[tile];
  if (!bound.relevant) {  // the whole block: no pixel to shade (the reference's early exit)
    if (threadIdx.x == 0) p.tile_candidates[tile] = 0;
    return;
  }
  const std::uint32_t x = (tile % p.tiles_x) * tile_size + threadIdx.x % tile_size;
  const std::uint32_t y = (tile / p.tiles_x) * tile_size + threadIdx.x / tile_size;
  const std::size_t pixel = std::size_t(y) * p.width + x;
  SofttileFragment fragment{};
  bool has_pixel = x < p.width && y < p.height;
  if (has_pixel) {
    fragment = p.fragments[pixel];
    has_pixel = fragment.relevant != 0;
  }
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
        if (triangle.triangle == fragment.receiver) continue;
        ++tests;
        float edges[9];
        if (!triangle_edges(fragment, p.raster.inverse_scale, triangle, edges)) continue;
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

inline void check(cudaError_t status, const char* call) {
  if (status == cudaSuccess) return;
  throw std::runtime_error(std::string("CUDA error in ") + call + ": " + cudaGetErrorName(status) +
                           ": " + cudaGetErrorString(status));
}

// Owns one device allocation.
template <typename T>
class DeviceArray {
 public:
  explicit DeviceArray(std::size_t count) : count_(count) {
    if (count_ != 0) check(cudaMalloc(&data_, count_ * sizeof(T)), "cudaMalloc");
  }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error in a destructor
  }
  T* data() const { return data_; }

  void upload(const std::vector<T>& host) {
    if (count_ != 0)
      check(cudaMemcpy(data_, host.data(), count_ * sizeof(T), cudaMemcpyHostToDevice),
            "cudaMemcpy to device");
  }
  void download(std::vector<T>& host) const {
    host.resize(count_);
    if (count_ != 0)
      check(cudaMemcpy(host.data(), data_, count_ * sizeof(T), cudaMemcpyDeviceToHost),
            "cudaMemcpy to host");
  }

 private:
  std::size_t count_;
  T* data_ = nullptr;
};

inline SofttileKernelResult run(const SofttileKernelInput& input) {
  const std::size_t pixels = std::size_t(input.width) * input.height;
  const std::size_t tiles = std::size_t(input.tiles_x) * input.tiles_y;
  if (input.fragments.size() != pixels || input.bounds.size() != tiles ||
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
  if (pixels == 0) return result;

  DeviceArray<SofttileFragment> fragments(pixels);
  DeviceArray<SofttileBound> bounds(tiles);
  DeviceArray<SofttileCluster> clusters(input.clusters.size());
  DeviceArray<SofttileCone> cones(input.triangle_cones.size());
  DeviceArray<SofttileTriangle> triangles(input.triangles.size());
  DeviceArray<float> visible(pixels);
  DeviceArray<std::uint32_t> tests(pixels), rasterized(pixels), candidates(tiles);
  fragments.upload(input.fragments);
  bounds.upload(input.bounds);
  clusters.upload(input.clusters);
  cones.upload(input.triangle_cones);
  triangles.upload(input.triangles);
  visible.upload(result.visible_fraction);
  tests.upload(result.tests);
  rasterized.upload(result.rasterized);

  KernelParams p{};
  p.width = input.width;
  p.height = input.height;
  p.tiles_x = input.tiles_x;
  p.fragments = fragments.data();
  p.bounds = bounds.data();
  p.clusters = clusters.data();
  p.cluster_count = static_cast<std::uint32_t>(input.clusters.size());
  p.triangle_cones = cones.data();
  p.triangles = triangles.data();
  p.sun = input.sun;
  p.raster = input.raster;
  p.batch_capacity = input.batch_capacity;
  p.visible_fraction = visible.data();
  p.tests = tests.data();
  p.rasterized = rasterized.data();
  p.tile_candidates = candidates.data();
  const std::size_t mask_words = input.record_masks ? pixels * softtile_kernel_max_rows : 0;
  DeviceArray<std::uint32_t> masks(mask_words);
  if (mask_words != 0)  // pixels without a relevant sample keep zero rows
    check(cudaMemset(masks.data(), 0, mask_words * sizeof(std::uint32_t)), "cudaMemset");
  p.masks = masks.data();
  // A list holds each gathered triangle at most once: room for all of them in every tile (the
  // tests' small frames only).
  p.triangle_count = static_cast<std::uint32_t>(input.triangles.size());
  DeviceArray<std::uint32_t> lists(input.record_candidates ? tiles * input.triangles.size() : 0);
  p.candidate_list = input.record_candidates ? lists.data() : nullptr;
  SHADOWCTS_LAUNCH(softtile_tiles, static_cast<unsigned>(tiles), threads_per_block, 0)(p);
  check(cudaGetLastError(), "softtile_tiles launch");
  check(cudaDeviceSynchronize(), "softtile_tiles");
  visible.download(result.visible_fraction);
  tests.download(result.tests);
  rasterized.download(result.rasterized);
  candidates.download(result.candidates);
  masks.download(result.masks);
  if (input.record_candidates) {
    std::vector<std::uint32_t> all;
    lists.download(all);
    result.candidate_offsets.assign(tiles + 1, 0);
    for (std::size_t t = 0; t < tiles; ++t) {
      result.candidate_offsets[t + 1] = result.candidate_offsets[t] + result.candidates[t];
      const auto first = all.begin() + std::ptrdiff_t(t * input.triangles.size());
      result.candidate_list.insert(result.candidate_list.end(), first,
                                   first + std::ptrdiff_t(result.candidates[t]));
    }
  }
  return result;
}

}  // namespace softtile
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
