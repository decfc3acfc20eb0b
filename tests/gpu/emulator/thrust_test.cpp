// Device-wide primitives under the emulator: Thrust with the TBB device system on the emulator's
// device memory, in the order a port uses them (keys written by a kernel, sorted, made unique,
// list sizes counted and scanned into offsets), against std:: on the host, for any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <thrust/execution_policy.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/unique.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "gpu/emulator/kernel.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::thrust_test {

__global__ void write_keys(std::uint32_t n, std::uint64_t* keys, std::uint32_t* values) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  keys[i] = (std::uint64_t{i} * 2654435761u) % 997u;  // many repeats, scattered
  values[i] = i;
}

struct SortedRuns {
  std::vector<std::uint64_t> keys, unique_keys;
  std::vector<std::uint32_t> values, offsets;
};

SortedRuns sort_unique_scan(std::uint32_t n) {
  std::uint64_t* keys = nullptr;
  std::uint32_t* values = nullptr;
  cudaMalloc(&keys, n * sizeof(std::uint64_t));
  cudaMalloc(&values, n * sizeof(std::uint32_t));
  SHADOWCTS_LAUNCH(write_keys, (n + 255) / 256, 256, 0)(n, keys, values);
  thrust::stable_sort_by_key(thrust::device, keys, keys + n, values);
  SortedRuns out;
  out.keys.resize(n);
  out.values.resize(n);
  cudaMemcpy(out.keys.data(), keys, n * sizeof(std::uint64_t), cudaMemcpyDeviceToHost);
  cudaMemcpy(out.values.data(), values, n * sizeof(std::uint32_t), cudaMemcpyDeviceToHost);
  std::uint64_t* end = thrust::unique(thrust::device, keys, keys + n);
  const auto runs = static_cast<std::uint32_t>(end - keys);
  out.unique_keys.resize(runs);
  cudaMemcpy(out.unique_keys.data(), keys, runs * sizeof(std::uint64_t), cudaMemcpyDeviceToHost);
  // Offsets of runs of equal length: count / exclusive scan, as list building does.
  std::uint32_t* counts = nullptr;
  cudaMalloc(&counts, (runs + 1) * sizeof(std::uint32_t));
  std::vector<std::uint32_t> host_counts(runs + 1, 0);
  for (std::uint32_t r = 0; r < runs; ++r) host_counts[r] = r % 5;
  cudaMemcpy(counts, host_counts.data(), host_counts.size() * sizeof(std::uint32_t),
             cudaMemcpyHostToDevice);
  thrust::exclusive_scan(thrust::device, counts, counts + runs + 1, counts);
  out.offsets.resize(runs + 1);
  cudaMemcpy(out.offsets.data(), counts, out.offsets.size() * sizeof(std::uint32_t),
             cudaMemcpyDeviceToHost);
  cudaFree(keys);
  cudaFree(values);
  cudaFree(counts);
  return out;
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::thrust_test

namespace shadowcts {
namespace {

TEST(EmulatorThrust, SortUniqueAndScanMatchTheHostOnEmulatedDeviceMemory) {
  constexpr std::uint32_t n = 100000;
  const auto got = emulated::thrust_test::sort_unique_scan(n);

  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  auto key = [](std::uint32_t i) { return (std::uint64_t{i} * 2654435761u) % 997u; };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
  ASSERT_EQ(got.values, order);  // stable: equal keys keep their index order
  for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(got.keys[i], key(order[i])) << i;
  ASSERT_EQ(got.unique_keys.size(), 997u);
  for (std::uint32_t k = 0; k < 997; ++k) EXPECT_EQ(got.unique_keys[k], k);
  std::uint32_t sum = 0;
  for (std::uint32_t r = 0; r <= 997; ++r) {
    EXPECT_EQ(got.offsets[r], sum) << r;
    if (r < 997) sum += r % 5;
  }
}

TEST(EmulatorThrust, SameResultsForAnyThreadCount) {
  const auto many = emulated::thrust_test::sort_unique_scan(50000);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const auto single = emulated::thrust_test::sort_unique_scan(50000);
  EXPECT_EQ(many.keys, single.keys);
  EXPECT_EQ(many.values, single.values);
  EXPECT_EQ(many.unique_keys, single.unique_keys);
  EXPECT_EQ(many.offsets, single.offsets);
}

}  // namespace
}  // namespace shadowcts
