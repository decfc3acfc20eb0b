#pragma once
// One macro marks geometry that runs on host and device, so a fix lands in every backend.
#if defined(__CUDACC__)
#define SHADOWCTS_HD __host__ __device__
#else
#define SHADOWCTS_HD
#endif

// Host TUs built to round like nvcc's default (--fmad=true: a*b+c contracted into one FMA; the
// emulated kernels, see gpu/CMakeLists.txt) define SHADOWCTS_FP_CONTRACT=1. The shared geometry
// then lives in an inline namespace of its own there, so its inline functions get other symbol
// names and the linker never hands a contracted copy to code built without contraction (or the
// reverse): the same source, two roundings, never mixed.
#if defined(SHADOWCTS_FP_CONTRACT) && SHADOWCTS_FP_CONTRACT && !defined(__CUDACC__)
#define SHADOWCTS_GEOMETRY_ABI_BEGIN inline namespace fp_contract {
#define SHADOWCTS_GEOMETRY_ABI_END }
#else
#define SHADOWCTS_GEOMETRY_ABI_BEGIN
#define SHADOWCTS_GEOMETRY_ABI_END
#endif
