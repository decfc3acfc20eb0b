#pragma once
// Correct kernels in the one dialect (gpu/emulator/kernel.h): they must give the right answer
// under every schedule, with race checking on.
#include <cstdint>

#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::test_kernels {

constexpr unsigned full_mask = 0xffffffffu;

// Tree reduction in shared memory, one partial sum per block, added to *total atomically.
__global__ void block_reduce_sum(const int* values, unsigned count, unsigned long long* total) {
  SHADOWCTS_SHARED(long long[256], partial);
  const unsigned tid = threadIdx.x;
  const unsigned i = blockIdx.x * blockDim.x + tid;
  partial[tid] = i < count ? static_cast<long long>(values[i]) : 0;
  __syncthreads();
  for (unsigned stride = blockDim.x / 2; stride > 0; stride /= 2) {
    if (tid < stride) partial[tid] += partial[tid + stride];
    __syncthreads();
  }
  if (tid == 0)
    atomicAdd(total, static_cast<unsigned long long>(static_cast<long long>(partial[0])));
}

// Warp shuffles inside each warp, one partial per warp in shared memory, the first warp
// reduces the partials with butterfly shuffles.
__global__ void warp_shuffle_reduce(const int* values, unsigned count, int* block_sums) {
  SHADOWCTS_SHARED(int[32], warp_sums);
  const unsigned tid = threadIdx.x;
  const unsigned i = blockIdx.x * blockDim.x + tid;
  int v = i < count ? values[i] : 0;
  for (int offset = warpSize / 2; offset > 0; offset /= 2)
    v += __shfl_down_sync(full_mask, v, offset);
  const unsigned warps = blockDim.x / warpSize;
  if (tid % warpSize == 0) warp_sums[tid / warpSize] = v;
  __syncthreads();
  if (tid < warpSize) {
    int w = tid < warps ? static_cast<int>(warp_sums[tid]) : 0;
    for (int mask = warpSize / 2; mask > 0; mask /= 2) w += __shfl_xor_sync(full_mask, w, mask);
    if (tid == 0) block_sums[blockIdx.x] = w;
  }
}

// Inclusive scan of one block: warp scans with __shfl_up_sync, warp totals scanned through
// shared memory. block_totals gets each block's sum.
__global__ void block_inclusive_scan(const int* values, unsigned count, int* out,
                                     int* block_totals) {
  SHADOWCTS_SHARED(int[32], warp_totals);
  const unsigned tid = threadIdx.x;
  const unsigned lane = tid % warpSize, warp = tid / warpSize;
  const unsigned i = blockIdx.x * blockDim.x + tid;
  int v = i < count ? values[i] : 0;
  for (unsigned d = 1; d < static_cast<unsigned>(warpSize); d *= 2) {
    const int up = __shfl_up_sync(full_mask, v, d);
    if (lane >= d) v += up;
  }
  if (lane == warpSize - 1) warp_totals[warp] = v;
  __syncthreads();
  if (warp == 0) {
    const unsigned warps = blockDim.x / warpSize;
    int t = lane < warps ? static_cast<int>(warp_totals[lane]) : 0;
    for (unsigned d = 1; d < static_cast<unsigned>(warpSize); d *= 2) {
      const int up = __shfl_up_sync(full_mask, t, d);
      if (lane >= d) t += up;
    }
    if (lane < warps) warp_totals[lane] = t;
  }
  __syncthreads();
  if (warp > 0) v += warp_totals[warp - 1];
  if (i < count) out[i] = v;
  if (tid == blockDim.x - 1) block_totals[blockIdx.x] = v;
}

// Adds the totals of the blocks before this one (second pass of a multi-block scan).
__global__ void add_block_offsets(int* out, unsigned count, const int* block_totals) {
  SHADOWCTS_SHARED(int, offset);
  if (threadIdx.x == 0) {
    int sum = 0;
    for (unsigned b = 0; b < blockIdx.x; ++b) sum += block_totals[b];
    offset = sum;
  }
  __syncthreads();
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < count) out[i] += offset;
}

// Tiled transpose through a padded shared tile (32 x 33 against bank conflicts), blocks of
// 32 x 8 threads, each moving 4 rows.
constexpr unsigned tile_dim = 32, tile_rows = 8;
__global__ void transpose(const float* in, float* out, unsigned width, unsigned height) {
  SHADOWCTS_SHARED(float[tile_dim][tile_dim + 1], tile);
  unsigned x = blockIdx.x * tile_dim + threadIdx.x;
  unsigned y = blockIdx.y * tile_dim + threadIdx.y;
  for (unsigned j = 0; j < tile_dim; j += tile_rows) {
    if (x < width && y + j < height) tile[threadIdx.y + j][threadIdx.x] = in[(y + j) * width + x];
  }
  __syncthreads();
  x = blockIdx.y * tile_dim + threadIdx.x;
  y = blockIdx.x * tile_dim + threadIdx.y;
  for (unsigned j = 0; j < tile_dim; j += tile_rows) {
    if (x < height && y + j < width) out[(y + j) * height + x] = tile[threadIdx.x][threadIdx.y + j];
  }
}

// Histogram in shared memory with shared atomics, merged into global bins; also every global
// atomic on one word each.
constexpr unsigned bins = 16;
struct AtomicResults {
  int add, min, max;
  unsigned and_bits, or_bits, xor_bits;
  unsigned long long add64;
  float add_float;
  int exch_flag, exch_winners, cas_count;
  unsigned max_shared;
};
__global__ void histogram_and_atomics(const unsigned* values, unsigned count, unsigned* histogram,
                                      AtomicResults* r) {
  SHADOWCTS_SHARED(unsigned[bins], local);
  SHADOWCTS_SHARED(unsigned, local_max);
  const unsigned tid = threadIdx.x;
  if (tid < bins) local[tid] = 0;
  if (tid == 0) local_max = 0;
  __syncthreads();
  const unsigned i = blockIdx.x * blockDim.x + tid;
  if (i < count) {
    const unsigned v = values[i];
    atomicAdd(&local[v % bins], 1u);
    atomicMax(&local_max, v);
    atomicAdd(&r->add, 1);
    atomicMin(&r->min, static_cast<int>(v));
    atomicMax(&r->max, static_cast<int>(v));
    atomicAnd(&r->and_bits, ~(1u << (v % 32)));
    atomicOr(&r->or_bits, 1u << (v % 32));
    atomicXor(&r->xor_bits, v);
    atomicAdd(&r->add64, 1ull << 33);
    atomicAdd(&r->add_float, 0.5f);
    if (atomicExch(&r->exch_flag, 1) == 0) atomicAdd(&r->exch_winners, 1);
    // An increment by compare-and-swap, as code without a native atomic for its type does.
    int old = atomicAdd(&r->cas_count, 0), assumed = 0;
    do {
      assumed = old;
      old = atomicCAS(&r->cas_count, assumed, assumed + 1);
    } while (old != assumed);
  }
  __syncthreads();
  if (tid < bins) atomicAdd(&histogram[tid], static_cast<unsigned>(local[tid]));
  if (tid == 0) atomicMax(&r->max_shared, static_cast<unsigned>(local_max));
}

// Votes, __activemask in a divergent branch, and the barrier predicates, written per thread.
struct VoteResults {
  unsigned ballot, active;
  int any, all, none_all;
  int count, and_all, and_some, or_some;
};
__global__ void votes(VoteResults* out) {
  const unsigned tid = threadIdx.x, lane = tid % warpSize;
  VoteResults r{};
  r.ballot = __ballot_sync(full_mask, lane % 3 == 0);
  r.any = __any_sync(full_mask, lane == 17);
  r.all = __all_sync(full_mask, lane < 32);
  r.none_all = __all_sync(full_mask, lane != 5);
  if (lane < 10) {
    r.active = __activemask();
  } else {
    r.active = __activemask();
  }
  r.count = __syncthreads_count(tid % 4 == 0);
  r.and_all = __syncthreads_and(tid < blockDim.x);
  r.and_some = __syncthreads_and(tid != 3);
  r.or_some = __syncthreads_or(tid == blockDim.x - 1);
  out[blockIdx.x * blockDim.x + tid] = r;
}

// Shuffles with a width and the out-of-range rules: idx wraps in its segment, up/down/xor past
// the segment return the caller's own value.
struct ShuffleResults {
  int idx, idx_wide, up, down, xor_in, xor_out;
};
__global__ void shuffle_rules(ShuffleResults* out) {
  const int lane = static_cast<int>(threadIdx.x % warpSize);
  ShuffleResults r{};
  r.idx = __shfl_sync(full_mask, lane, 3, 8);
  r.idx_wide = __shfl_sync(full_mask, lane, 11, 8);
  r.up = __shfl_up_sync(full_mask, lane, 2, 8);
  r.down = __shfl_down_sync(full_mask, lane, 3, 8);
  r.xor_in = __shfl_xor_sync(full_mask, lane, 1, 8);
  r.xor_out = __shfl_xor_sync(full_mask, lane, 8, 8);
  out[threadIdx.x] = r;
}

// Reverses each block's slice through dynamic shared memory.
__global__ void reverse_dynamic(const int* in, int* out, unsigned count) {
  SHADOWCTS_DYNAMIC_SHARED(int, buffer);
  const unsigned tid = threadIdx.x;
  const unsigned i = blockIdx.x * blockDim.x + tid;
  if (i < count) buffer[tid] = in[i];
  __syncthreads();
  // count is a multiple of the block size here: every slot was written before the barrier.
  if (i < count) out[i] = buffer[blockDim.x - 1 - tid];
}

// The last warp of a shared-memory reduction, warp-synchronous with __syncwarp between steps.
__global__ void warp_synchronous_reduce(const int* values, int* block_sums) {
  SHADOWCTS_SHARED(int[64], s);
  const unsigned tid = threadIdx.x;
  s[tid] = values[blockIdx.x * 64 + tid];
  __syncthreads();
  if (tid < 32) {
    int v = static_cast<int>(s[tid]) + static_cast<int>(s[tid + 32]);
    for (unsigned offset = 16; offset > 0; offset /= 2) {
      __syncwarp();
      s[tid] = v;
      __syncwarp();
      v += s[tid + offset];
    }
    if (tid == 0) block_sums[blockIdx.x] = v;
  }
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::test_kernels
