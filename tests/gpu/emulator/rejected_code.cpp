// Code the emulator must refuse to compile rather than run silently wrong. Built by CTest with
// -fsyntax-only, once per case: with SHADOWCTS_GOOD=1 the correct line must compile (so a case
// cannot pass by a typo), with SHADOWCTS_GOOD=0 the wrong one must not.
#include "gpu/emulator/kernel.h"

#ifndef SHADOWCTS_GOOD
#error "compile with -DSHADOWCTS_GOOD=0 or 1 and -DSHADOWCTS_CASE=<name>"
#endif
#define CASE(name) (SHADOWCTS_CASE_##name == SHADOWCTS_CASE)
#define SHADOWCTS_CASE_raw_shared 1
#define SHADOWCTS_CASE_member_access 2
#define SHADOWCTS_CASE_escaped_proxy 3
#define SHADOWCTS_CASE_shared_pointer 4
#define SHADOWCTS_CASE_legacy_shuffle 5
#define SHADOWCTS_CASE_constant_memory 6
#define SHADOWCTS_CASE_atomic_type 7
#define SHADOWCTS_CASE_math_function 8

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {

struct Pair {
  float x, y;
};

#if CASE(constant_memory) && !SHADOWCTS_GOOD
__constant__ float table[4];
#endif

__global__ void kernel(float* out) {
  SHADOWCTS_SHARED(Pair[32], pairs);
  SHADOWCTS_SHARED(int[32], ints);
  const unsigned tid = threadIdx.x;
#if CASE(raw_shared)
#if SHADOWCTS_GOOD
  SHADOWCTS_SHARED(float[32], staged);
#else
  __shared__ float staged[32];
#endif
  staged[tid] = 1.0f;
#elif CASE(member_access)
#if SHADOWCTS_GOOD
  pairs[tid] = Pair{1.0f, 2.0f};
#else
  pairs[tid].x = 1.0f;
#endif
#elif CASE(escaped_proxy)
#if SHADOWCTS_GOOD
  const int v = ints[tid];
#else
  auto r = ints[tid];  // a proxy that would read later, outside the tracking
  const int v = r;
#endif
  out[tid] = static_cast<float>(v);
#elif CASE(shared_pointer)
#if SHADOWCTS_GOOD
  atomicAdd(&ints[tid], 1);
#else
  int* p = &ints[tid];
  *p = 1;
#endif
#elif CASE(legacy_shuffle)
  float v = out[tid];
#if SHADOWCTS_GOOD
  v = __shfl_sync(0xffffffffu, v, 0);
#else
  v = __shfl(v, 0);  // the pre-Volta shuffle without a mask
#endif
  out[tid] = v;
#elif CASE(constant_memory)
  out[tid] = 1.0f;
#elif CASE(atomic_type)
#if SHADOWCTS_GOOD
  atomicMin(reinterpret_cast<int*>(out), 1);
#else
  atomicMin(out, 1.0f);  // CUDA has no float atomicMin
#endif
#elif CASE(math_function)
#if SHADOWCTS_GOOD
  out[tid] = out[tid] < 1.0f ? out[tid] : 1.0f;
#else
  out[tid] = __saturatef(out[tid]);  // an intrinsic the emulator does not provide
#endif
#else
#error "unknown SHADOWCTS_CASE"
#endif
  (void)pairs;
  (void)ints;
  (void)out;
  (void)tid;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
