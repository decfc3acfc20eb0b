#pragma once
// Kernels with one bug each, the kind a GPU hangs on or gets silently wrong. The line each
// report must name carries a `BUG:<name>` comment; the test finds it in this file.
#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::bug_kernels {

inline const char* source_file = __FILE__;
constexpr unsigned full_mask = 0xffffffffu;

// Thread 5 returns before the barrier the others wait at.
__global__ void exit_before_barrier(int* out) {
  SHADOWCTS_SHARED(int[64], s);
  s[threadIdx.x] = static_cast<int>(threadIdx.x);
  if (threadIdx.x == 5) return;
  __syncthreads();  // BUG:exit_before_barrier
  out[threadIdx.x] = s[(threadIdx.x + 1) % 64];
}

// Half the block waits at one barrier, half at another.
__global__ void different_barriers(int* out) {
  if (threadIdx.x < 32) {
    __syncthreads();
  } else {
    __syncthreads();  // BUG:different_barriers
  }
  out[threadIdx.x] = 1;
}

// Lane 3 goes to a block barrier while the rest of its warp shuffles with a full mask.
__global__ void lane_misses_shuffle(int* out) {
  int v = static_cast<int>(threadIdx.x);
  if (threadIdx.x == 3) {
    __syncthreads();
  } else {
    v = __shfl_sync(full_mask, v, 0);  // BUG:lane_misses_shuffle
    __syncthreads();
  }
  out[threadIdx.x] = v;
}

// Lane 7 has returned when the others shuffle with a full mask.
__global__ void lane_exited_before_shuffle(int* out) {
  int v = static_cast<int>(threadIdx.x);
  if (threadIdx.x == 7) return;
  v += __shfl_down_sync(full_mask, v, 1);  // BUG:lane_exited_before_shuffle
  out[threadIdx.x] = v;
}

// A 48-thread block: the full mask of the second warp names 16 lanes that do not exist.
__global__ void partial_warp_shuffle(int* out) {
  int v = static_cast<int>(threadIdx.x);
  v += __shfl_xor_sync(full_mask, v, 1);  // BUG:partial_warp_shuffle
  out[threadIdx.x] = v;
}

// The lower half-warp shuffles down by 8 with a half-warp mask: lanes 8..15 read 16..23.
__global__ void shuffle_from_inactive_lane(int* out) {
  int v = static_cast<int>(threadIdx.x);
  if (threadIdx.x < 16) {
    v = __shfl_down_sync(0x0000ffffu, v, 8);  // BUG:shuffle_from_inactive_lane
  }
  out[threadIdx.x] = v;
}

// Each thread reads its left neighbour's slot with no barrier after the writes. Run-until-block
// happens to give the right answer (the neighbour ran first); a random schedule does not.
__global__ void missing_barrier(const int* in, int* out) {
  SHADOWCTS_SHARED(int[128], s);
  const unsigned tid = threadIdx.x;
  s[tid] = in[tid];
  out[tid] = tid > 0 ? static_cast<int>(s[tid - 1]) : 0;  // BUG:missing_barrier
}

// A staging loop without the barrier that keeps the previous tile alive: thread t overwrites
// s[t] while thread t-1 may still read it.
__global__ void tile_overwritten_while_read(const int* in, int* out, unsigned tiles) {
  SHADOWCTS_SHARED(int[64], s);
  const unsigned tid = threadIdx.x;
  int sum = 0;
  for (unsigned t = 0; t < tiles; ++t) {
    s[tid] = in[t * 64 + tid];  // BUG:tile_overwritten_while_read
    __syncthreads();
    sum += s[(tid + 1) % 64];
  }
  out[tid] = sum;
}

// The classic warp-synchronous tail of a reduction, without __syncwarp between the steps.
__global__ void warp_synchronous_without_syncwarp(const int* in, int* out) {
  SHADOWCTS_SHARED(int[64], s);
  const unsigned tid = threadIdx.x;
  s[tid] = in[tid];
  __syncthreads();
  if (tid < 32) {
    s[tid] += s[tid + 32];  // BUG:warp_synchronous_without_syncwarp
    s[tid] += s[tid + 16];
    s[tid] += s[tid + 8];
    s[tid] += s[tid + 4];
    s[tid] += s[tid + 2];
    s[tid] += s[tid + 1];
  }
  if (tid == 0) out[0] = s[0];
}

// Each half-warp syncs with its own half mask, then lane 16 reads lane 0's write: no
// __syncwarp ordered the two (both halves synced, but not together).
__global__ void half_warp_syncwarp(int* out) {
  SHADOWCTS_SHARED(int[32], s);
  const unsigned lane = threadIdx.x;
  s[lane] = static_cast<int>(lane);
  __syncwarp(lane < 16 ? 0x0000ffffu : 0xffff0000u);
  // Within its half the read is ordered; lane 16 crosses to the other half.
  const unsigned source = lane == 16 ? 0 : (lane < 16 ? 15 - lane : 47 - lane);
  out[lane] = s[source];  // BUG:half_warp_syncwarp
}

// Lanes 0 and 1 wait at different collectives with the same mask: neither can complete.
__global__ void mismatched_collectives(int* out) {
  int v = static_cast<int>(threadIdx.x);
  if (threadIdx.x == 0) {
    v = __shfl_sync(0x3u, v, 1);  // BUG:mismatched_collectives
  } else {
    v = static_cast<int>(__ballot_sync(0x3u, v));
  }
  out[threadIdx.x] = v;
}

// Thread 9 reads a shared slot no thread has written.
__global__ void uninitialized_shared_read(int* out) {
  SHADOWCTS_SHARED(int[32], s);
  if (threadIdx.x != 9) s[threadIdx.x] = 1;
  __syncthreads();
  out[threadIdx.x] = s[threadIdx.x];  // BUG:uninitialized_shared_read
}

// One past the end of a shared array.
__global__ void shared_out_of_bounds(int* out) {
  SHADOWCTS_SHARED(int[32], s);
  s[threadIdx.x] = 1;
  __syncthreads();
  out[threadIdx.x] = s[threadIdx.x + 1];  // BUG:shared_out_of_bounds
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::bug_kernels
