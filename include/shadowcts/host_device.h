#pragma once
// One macro marks geometry that runs on host and device, so a fix lands in every backend.
#if defined(__CUDACC__)
#define SHADOWCTS_HD __host__ __device__
#else
#define SHADOWCTS_HD
#endif
