// Brute-force hard shadows on the GPU: one thread per view sample tests every caster triangle with
// the shared watertight segment/triangle test. Casters are staged through shared memory one tile at
// a time, so a block reads each triangle from global memory once.
#include <cuda_runtime.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/cuda_check.h"
#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts {
namespace {

constexpr int threads_per_block = 256;
constexpr int casters_per_tile = threads_per_block;  // each thread stages one caster per tile

struct TileCaster {
  float vertices[9];
  std::uint32_t triangle;
};

__global__ void bruteforce_hard_shadow(const glm::vec3* sample_positions,
                                       const std::uint32_t* sample_receivers,
                                       std::uint32_t sample_count, const BruteforceCaster* casters,
                                       std::uint32_t caster_count, bool directional_light,
                                       glm::vec3 light, std::uint8_t* shadowed,
                                       unsigned long long* pair_tests) {
  __shared__ TileCaster tile[casters_per_tile];
  const std::uint32_t sample = blockIdx.x * blockDim.x + threadIdx.x;
  const bool has_sample = sample < sample_count;

  RaySpace ray;
  std::uint32_t receiver = 0;
  if (has_sample) {
    const glm::vec3 position = sample_positions[sample];
    ray = make_ray_space(directional_light ? ray_to_directional_light(position, light)
                                           : segment_to_point_light(position, light));
    receiver = sample_receivers[sample];
  }
  bool done = !has_sample;  // shadowed, or no sample to shade
  bool hit = false;
  unsigned long long tests = 0;

  for (std::uint32_t tile_start = 0; tile_start < caster_count; tile_start += casters_per_tile) {
    // Also the barrier that keeps the previous tile alive until every thread is past it.
    if (!__syncthreads_or(!done)) break;
    const std::uint32_t staged = tile_start + threadIdx.x;
    if (staged < caster_count) {
      const BruteforceCaster& caster = casters[staged];
      TileCaster& slot = tile[threadIdx.x];
      slot.vertices[0] = caster.v0.x;
      slot.vertices[1] = caster.v0.y;
      slot.vertices[2] = caster.v0.z;
      slot.vertices[3] = caster.v1.x;
      slot.vertices[4] = caster.v1.y;
      slot.vertices[5] = caster.v1.z;
      slot.vertices[6] = caster.v2.x;
      slot.vertices[7] = caster.v2.y;
      slot.vertices[8] = caster.v2.z;
      slot.triangle = caster.triangle;
    }
    __syncthreads();
    if (done) continue;
    const std::uint32_t tile_size =
        min(static_cast<std::uint32_t>(casters_per_tile), caster_count - tile_start);
    for (std::uint32_t i = 0; i < tile_size; ++i) {
      const TileCaster& caster = tile[i];  // every lane reads the same slot: a broadcast
      ++tests;  // the receiver counts as a visited pair, as in the reference backend
      if (caster.triangle == receiver) continue;
      const float* v = caster.vertices;
      if (ray_hits_triangle(ray, glm::vec3(v[0], v[1], v[2]), glm::vec3(v[3], v[4], v[5]),
                            glm::vec3(v[6], v[7], v[8]))) {
        hit = true;
        done = true;
        break;
      }
    }
  }

  if (has_sample) shadowed[sample] = hit ? 1 : 0;
  // Integer sums are order-independent, so the total is deterministic.
  for (int offset = warpSize / 2; offset > 0; offset /= 2) {
    tests += __shfl_down_sync(0xffffffffu, tests, offset);
  }
  if (threadIdx.x % warpSize == 0 && tests != 0) atomicAdd(pair_tests, tests);
}

// Owns one cudaMalloc allocation.
template <typename T>
class DeviceArray {
 public:
  explicit DeviceArray(std::size_t count) : count_(count) {
    if (count_ != 0) check_cuda(cudaMalloc(&data_, count_ * sizeof(T)), "cudaMalloc");
  }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  ~DeviceArray() {
    if (data_ != nullptr) cudaFree(data_);  // nothing useful to do with an error in a destructor
  }
  T* data() const { return data_; }

  void upload(const std::vector<T>& host) {
    if (count_ != 0) {
      check_cuda(cudaMemcpy(data_, host.data(), count_ * sizeof(T), cudaMemcpyHostToDevice),
                 "cudaMemcpy to device");
    }
  }
  void download(T* host) const {
    if (count_ != 0) {
      check_cuda(cudaMemcpy(host, data_, count_ * sizeof(T), cudaMemcpyDeviceToHost),
                 "cudaMemcpy to host");
    }
  }

 private:
  std::size_t count_;
  T* data_ = nullptr;
};

}  // namespace

BruteforceShadowResult run_bruteforce_hard_shadow_kernel(const BruteforceShadowInput& input) {
  const std::size_t sample_count = input.sample_positions.size();
  BruteforceShadowResult result;
  result.shadowed.assign(sample_count, 0);
  if (sample_count == 0 || input.casters.empty()) return result;
  if (sample_count > UINT32_MAX || input.casters.size() > UINT32_MAX) {
    throw std::length_error("bruteforce_hard_shadow: more than 2^32 samples or casters");
  }

  DeviceArray<glm::vec3> positions(sample_count);
  DeviceArray<std::uint32_t> receivers(sample_count);
  DeviceArray<BruteforceCaster> casters(input.casters.size());
  DeviceArray<std::uint8_t> shadowed(sample_count);
  DeviceArray<unsigned long long> pair_tests(1);
  positions.upload(input.sample_positions);
  receivers.upload(input.sample_receivers);
  casters.upload(input.casters);
  check_cuda(cudaMemset(pair_tests.data(), 0, sizeof(unsigned long long)), "cudaMemset");

  const auto block_count =
      static_cast<unsigned>((sample_count + threads_per_block - 1) / threads_per_block);
  bruteforce_hard_shadow<<<block_count, threads_per_block>>>(
      positions.data(), receivers.data(), static_cast<std::uint32_t>(sample_count), casters.data(),
      static_cast<std::uint32_t>(input.casters.size()), input.directional_light, input.light,
      shadowed.data(), pair_tests.data());
  check_cuda(cudaGetLastError(), "bruteforce_hard_shadow launch");
  check_cuda(cudaDeviceSynchronize(), "bruteforce_hard_shadow");

  shadowed.download(result.shadowed.data());
  unsigned long long total_tests = 0;
  pair_tests.download(&total_tests);
  result.pair_tests = total_tests;
  return result;
}

}  // namespace shadowcts
