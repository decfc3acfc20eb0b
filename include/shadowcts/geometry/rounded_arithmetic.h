#pragma once
// Arithmetic with exactly one IEEE round-to-nearest rounding per operation, written once for host
// and device. nvcc fuses a*b+c into one FMA by default (--fmad=true); the __f*_rn / __d*_rn
// intrinsics are never fused, so device results equal those of host code compiled without FMA
// contraction (the x86-64 default) and of the emulated kernels, which contract the rest as nvcc
// does (SHADOWCTS_FP_CONTRACT). The watertight triangle test relies on this only for
// bit-exact host/device agreement: its sign decisions stay exact even where a host compiler does
// contract (see segment_triangle.h).
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

SHADOWCTS_HD inline float rounded_add(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fadd_rn(a, b);
#else
  return a + b;
#endif
}

SHADOWCTS_HD inline float rounded_sub(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fsub_rn(a, b);
#else
  return a - b;
#endif
}

SHADOWCTS_HD inline float rounded_mul(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fmul_rn(a, b);
#elif defined(SHADOWCTS_FP_CONTRACT) && SHADOWCTS_FP_CONTRACT
  // A TU that contracts like nvcc: the volatile keeps this product from fusing with an add.
  volatile float product = a * b;
  return product;
#else
  return a * b;
#endif
}

SHADOWCTS_HD inline float rounded_div(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fdiv_rn(a, b);
#else
  return a / b;
#endif
}

SHADOWCTS_HD inline double rounded_add(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dadd_rn(a, b);
#else
  return a + b;
#endif
}

SHADOWCTS_HD inline double rounded_sub(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dsub_rn(a, b);
#else
  return a - b;
#endif
}

SHADOWCTS_HD inline double rounded_mul(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dmul_rn(a, b);
#elif defined(SHADOWCTS_FP_CONTRACT) && SHADOWCTS_FP_CONTRACT
  // A TU that contracts like nvcc: the volatile keeps this product from fusing with an add.
  volatile double product = a * b;
  return product;
#else
  return a * b;
#endif
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
