#pragma once
// The one dialect kernel bodies (.cuh) are written in, so the same source compiles under nvcc
// (real CUDA) and under the host compiler against the emulator (gpu/emulator/emulator.h).
//
//   __global__ / __device__           as in CUDA
//   SHADOWCTS_SHARED(type, name)      `__shared__ type name;` (type may be an array: float[32][33])
//   SHADOWCTS_DYNAMIC_SHARED(T, name) `extern __shared__ T name[];`
//   SHADOWCTS_LAUNCH(kernel, grid, block, shared)(args...)   instead of <<<grid, block, shared>>>
//   SHADOWCTS_KERNEL_NAMESPACE        `device` under nvcc, `emulated` on the host: put a .cuh's
//                                     definitions in shadowcts::SHADOWCTS_KERNEL_NAMESPACE so the
//                                     two builds of one kernel never share a symbol
//
// Under the emulator, shared memory is read and written by whole elements (`tile[i] = v;`,
// `T v = tile[i];`, `&tile[i]` for atomics); raw `__shared__`, `__constant__`, member access
// into shared structs, pointers to shared memory and CUDA functions the emulator lacks do not
// compile there.
#include <type_traits>

namespace shadowcts::kernel_detail {
// Lets one macro declare scalars and arrays: `type_t<float[4]> name;` declares `float name[4]`.
template <typename T>
using type_t = T;
}  // namespace shadowcts::kernel_detail

#if defined(__CUDACC__)

#include <cuda_runtime.h>

#define SHADOWCTS_KERNEL_NAMESPACE device
#define SHADOWCTS_EMULATED 0
#define SHADOWCTS_SHARED(type, name) __shared__ ::shadowcts::kernel_detail::type_t<type> name
#define SHADOWCTS_DYNAMIC_SHARED(type, name) extern __shared__ type name[]
#define SHADOWCTS_LAUNCH(kernel, grid, block, shared) kernel<<<(grid), (block), (shared)>>>

#else

#include "gpu/emulator/emulator.h"

#define SHADOWCTS_KERNEL_NAMESPACE emulated
#define SHADOWCTS_EMULATED 1

#define __global__
#define __device__
#define __host__
#define __forceinline__ inline

// A function-local static identifies the declaration, so every thread of a block (and every
// call of a device function) finds the same object in the block's shared arena.
#define SHADOWCTS_SHARED(type, name)                                              \
  static const ::shadowcts::emu::detail::SharedDecl name##_shadowcts_decl{        \
      sizeof(::shadowcts::kernel_detail::type_t<type>),                           \
      alignof(::shadowcts::kernel_detail::type_t<type>), #name};                  \
  ::shadowcts::emu::SharedVar<::shadowcts::kernel_detail::type_t<type>> name =    \
      ::shadowcts::emu::declare_shared<::shadowcts::kernel_detail::type_t<type>>( \
          name##_shadowcts_decl)
#define SHADOWCTS_DYNAMIC_SHARED(type, name) ::shadowcts::emu::SharedDynamic<type> name
#define SHADOWCTS_LAUNCH(kernel, grid, block, shared) \
  ::shadowcts::emu::Launch(kernel, #kernel, (grid), (block), (shared))

#define threadIdx (::shadowcts::emu::detail::this_thread().thread_idx)
#define blockIdx (::shadowcts::emu::detail::this_thread().block_idx)
#define blockDim (::shadowcts::emu::detail::this_thread().block_dim)
#define gridDim (::shadowcts::emu::detail::this_thread().grid_dim)
#define warpSize (::shadowcts::emu::warp_size)
#define dim3 ::shadowcts::emu::Dim3

#define __syncthreads ::shadowcts::emu::syncthreads
#define __syncthreads_count ::shadowcts::emu::syncthreads_count
#define __syncthreads_and ::shadowcts::emu::syncthreads_and
#define __syncthreads_or ::shadowcts::emu::syncthreads_or
#define __syncwarp ::shadowcts::emu::syncwarp
#define __shfl_sync ::shadowcts::emu::shfl_sync
#define __shfl_up_sync ::shadowcts::emu::shfl_up_sync
#define __shfl_down_sync ::shadowcts::emu::shfl_down_sync
#define __shfl_xor_sync ::shadowcts::emu::shfl_xor_sync
#define __ballot_sync ::shadowcts::emu::ballot_sync
#define __any_sync ::shadowcts::emu::any_sync
#define __all_sync ::shadowcts::emu::all_sync
#define __activemask ::shadowcts::emu::activemask

#define atomicAdd ::shadowcts::emu::atomic_add
#define atomicMin ::shadowcts::emu::atomic_min
#define atomicMax ::shadowcts::emu::atomic_max
#define atomicAnd ::shadowcts::emu::atomic_and
#define atomicOr ::shadowcts::emu::atomic_or
#define atomicXor ::shadowcts::emu::atomic_xor
#define atomicExch ::shadowcts::emu::atomic_exch
#define atomicCAS ::shadowcts::emu::atomic_cas

#define cudaError_t ::shadowcts::emu::EmuError
#define cudaSuccess ::shadowcts::emu::cudaSuccess
#define cudaMemcpyKind ::shadowcts::emu::EmuMemcpyKind
#define cudaMemcpyHostToDevice ::shadowcts::emu::cudaMemcpyHostToDevice
#define cudaMemcpyDeviceToHost ::shadowcts::emu::cudaMemcpyDeviceToHost
#define cudaMemcpyDeviceToDevice ::shadowcts::emu::cudaMemcpyDeviceToDevice
#define cudaMalloc ::shadowcts::emu::device_malloc
#define cudaFree ::shadowcts::emu::device_free
#define cudaMemcpy ::shadowcts::emu::device_memcpy
#define cudaMemset ::shadowcts::emu::device_memset
#define cudaDeviceSynchronize ::shadowcts::emu::device_synchronize
#define cudaGetLastError ::shadowcts::emu::get_last_error
#define cudaGetErrorName ::shadowcts::emu::error_name
#define cudaGetErrorString ::shadowcts::emu::error_string

#endif
