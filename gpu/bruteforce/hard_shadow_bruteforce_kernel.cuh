#pragma once
// Brute-force hard shadows, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda`
// backend, the host compiler into `cuda-emu` against the emulator. One thread per view sample
// tests every caster triangle with the shared watertight segment/triangle test; casters are
// staged through shared memory one tile at a time, so a block reads each triangle from global
// memory once.
//
// A caster whose box misses the exact segment's (shadowcts/geometry/segment_box.h) is skipped
// before the ray-space transform, most of a pair's cost. A hit the float test is certain of lies
// inside both boxes, so only uncertain answers about casters the exact segment misses are left
// out: fewer samples come back unsure, none changes its exact answer.
//
// The float test is exact for one perturbation of each triangle's vertices and of L - p; beside
// an edge its miss may be a crack (a T-junction) and its hit a rounding of L - p near the light,
// and at the light's end of the segment (triangle_reaches_light_end) either answer may be such a
// rounding; so a sample that no triangle hits away from its edges and the light's end but that
// passes near an edge or a triangle at that end comes back `unsure` and the host decides it
// exactly.
//
// The receiver half-space rule (shadowcts/geometry/receiver_half_space.h) is decided exactly on
// the device for every caster the float test hits or passes beside: one that cannot shadow the
// sample (a coplanar neighbour of the receiver, the next face of a convex mesh) neither ends the
// search nor makes the sample unsure. Its exact expansion products need a large stack: 69 KB per
// thread on the device (ptxas, sm_90, cumulative), about 38 KB on the host (GCC -O3,
// -fstack-usage: kernel, counts_for_sample, hit_on_light_side, sign_of_product_difference),
// within the emulator's 256 KB fiber stacks.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "shadowcts/geometry/edge_proximity.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_box.h"
#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace bruteforce {

constexpr int threads_per_block = 256;
constexpr int casters_per_tile = threads_per_block;  // each thread stages one caster per tile

struct TileCaster {
  float vertices[9];
  FloatBox box;  // the triangle's bounding box
  std::uint32_t triangle;
};

// The rule's exact expansions, inlined, took the kernel from 56 to 255 registers (ptxas, sm_90):
// a quarter of the occupancy for a path most pairs never take. Out of line and with the kernel
// bounded to the old occupancy (4 blocks per SM, 64 registers), nearly all spills stay in the
// rule.
#if SHADOWCTS_EMULATED
#define SHADOWCTS_BRUTEFORCE_OUT_OF_LINE
#define SHADOWCTS_BRUTEFORCE_LAUNCH_BOUNDS
#else
#define SHADOWCTS_BRUTEFORCE_OUT_OF_LINE __noinline__
#define SHADOWCTS_BRUTEFORCE_LAUNCH_BOUNDS __launch_bounds__(threads_per_block, 4)
#endif

// The receiver half-space rule for a caster the float test hits or passes beside, exact for the
// point where the segment's line crosses the caster's plane, so a caster it rejects cannot shadow
// the sample whether or not it meets the segment. The sample's half-space is built at the first
// call.
SHADOWCTS_BRUTEFORCE_OUT_OF_LINE __device__ bool counts_for_sample(
    geometry::ReceiverHalfSpace& half_space, bool& has_half_space,
    const BruteforceReceiver* receiver, bool directional_light, const glm::vec3& light,
    const glm::vec3& position, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  if (!has_half_space) {
    const BruteforceReceiver r = *receiver;
    half_space = geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2),
                                               directional_light, glm::dvec3(light));
    has_half_space = true;
  }
  return geometry::caster_counts(half_space, glm::dvec3(position), glm::dvec3(v0), glm::dvec3(v1),
                                 glm::dvec3(v2));
}

__global__ void SHADOWCTS_BRUTEFORCE_LAUNCH_BOUNDS bruteforce_hard_shadow(
    const glm::vec3* sample_positions, const std::uint32_t* sample_receivers,
    const BruteforceReceiver* sample_receiver_triangles, std::uint32_t sample_count,
    const BruteforceCaster* casters, std::uint32_t caster_count, bool directional_light,
    glm::vec3 light, std::uint8_t* sample_states, unsigned long long* pair_tests,
    unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  SHADOWCTS_SHARED(TileCaster[casters_per_tile], tile);
  const std::uint32_t sample = blockIdx.x * blockDim.x + threadIdx.x;
  const bool has_sample = sample < sample_count;

  RaySpace ray;
  FloatBox segment{};
  std::uint32_t receiver = 0;
  glm::vec3 position(0.0f);
  if (has_sample) {
    position = sample_positions[sample];
    ray = make_ray_space(directional_light ? ray_to_directional_light(position, light)
                                           : segment_to_point_light(position, light));
    segment = segment_box(position, light, directional_light);
    receiver = sample_receivers[sample];
  }
  // The rule's half-space, built by counts_for_sample at its first call.
  geometry::ReceiverHalfSpace half_space;
  bool has_half_space = false;
  bool done = !has_sample;  // shadowed, or no sample to shade
  bool hit = false, left_unsure = false;
  unsigned long long tests = 0;

  for (std::uint32_t tile_start = 0; tile_start < caster_count; tile_start += casters_per_tile) {
    // Also the barrier that keeps the previous tile alive until every thread is past it.
    if (!__syncthreads_or(!done)) break;
    const std::uint32_t staged = tile_start + threadIdx.x;
    if (staged < caster_count) {
      const BruteforceCaster& caster = casters[staged];
      TileCaster slot;
      slot.vertices[0] = caster.v0.x;
      slot.vertices[1] = caster.v0.y;
      slot.vertices[2] = caster.v0.z;
      slot.vertices[3] = caster.v1.x;
      slot.vertices[4] = caster.v1.y;
      slot.vertices[5] = caster.v1.z;
      slot.vertices[6] = caster.v2.x;
      slot.vertices[7] = caster.v2.y;
      slot.vertices[8] = caster.v2.z;
      slot.box = triangle_box(caster.v0, caster.v1, caster.v2);
      slot.triangle = caster.triangle;
      tile[threadIdx.x] = slot;
    }
    __syncthreads();
    if (done) continue;
    const std::uint32_t remaining = caster_count - tile_start;
    const std::uint32_t tile_size =
        remaining < std::uint32_t{casters_per_tile} ? remaining : std::uint32_t{casters_per_tile};
    for (std::uint32_t i = 0; i < tile_size; ++i) {
      const TileCaster caster = tile[i];  // every lane reads the same slot: a broadcast
      ++tests;  // the receiver counts as a visited pair, as in the reference backend
      if (caster.triangle == receiver || !boxes_overlap(caster.box, segment)) continue;
      const float* v = caster.vertices;
      const glm::vec3 v0(v[0], v[1], v[2]), v1(v[3], v[4], v[5]), v2(v[6], v[7], v[8]);
      const bool float_hit = ray_hits_triangle(ray, v0, v1, v2);
      // Beside an edge neither answer of the float test is certain: a miss may be a crack, a hit
      // may come from the rounding of L - p at the light end (stiff.light_1e-6_from_caster). At
      // the light's end of the segment neither is certain either, edge or not: a crossing of the
      // caster's plane within rounding of L (stiff.light_1ulp_off_caster_face). Only a hit away
      // from both ends the search; the host decides the samples left unsure.
      const bool unsure =
          (float_hit || !left_unsure) && (ray_within_rounding_of_triangle_edge(ray, v0, v1, v2) ||
                                          triangle_reaches_light_end(ray, v0, v1, v2));
      if (!float_hit && !unsure) continue;
      if (!counts_for_sample(half_space, has_half_space, sample_receiver_triangles + sample,
                             directional_light, light, position, v0, v1, v2))
        continue;
      if (float_hit && !unsure) {
        hit = true;
        done = true;
        break;
      }
      left_unsure = left_unsure || unsure;
    }
  }

  if (has_sample) {
    sample_states[sample] = hit           ? bruteforce_sample_shadowed
                            : left_unsure ? bruteforce_sample_unsure
                                          : bruteforce_sample_lit;
  }
  // Integer sums are order-independent, so the total is deterministic.
  for (int offset = warpSize / 2; offset > 0; offset /= 2) {
    tests += __shfl_down_sync(0xffffffffu, tests, offset);
  }
  if (threadIdx.x % warpSize == 0 && tests != 0) atomicAdd(pair_tests, tests);
}

// Takes the input by value: each host array is freed once uploaded.
inline BruteforceShadowResult run(BruteforceShadowInput input) {
  const std::size_t sample_count = input.sample_positions.size();
  BruteforceShadowResult result;
  result.shadowed.assign(sample_count, bruteforce_sample_lit);
  if (sample_count == 0 || input.casters.empty()) return result;
  if (sample_count > UINT32_MAX || input.casters.size() > UINT32_MAX) {
    throw std::length_error("bruteforce_hard_shadow: more than 2^32 samples or casters");
  }
  if (input.sample_receivers.size() != sample_count ||
      input.sample_receiver_triangles.size() != sample_count) {
    throw std::invalid_argument(
        "bruteforce_hard_shadow: one receiver and receiver triangle per sample");
  }

  const auto caster_count = static_cast<std::uint32_t>(input.casters.size());
  const DeviceArray<glm::vec3> positions = upload_and_free(input.sample_positions);
  const DeviceArray<std::uint32_t> receivers = upload_and_free(input.sample_receivers);
  const DeviceArray<BruteforceReceiver> receiver_triangles =
      upload_and_free(input.sample_receiver_triangles);
  const DeviceArray<BruteforceCaster> casters = upload_and_free(input.casters);
  DeviceArray<std::uint8_t> states(sample_count);
  DeviceArray<unsigned long long> pair_tests(1);
  pair_tests.zero();

  const auto block_count =
      static_cast<unsigned>((sample_count + threads_per_block - 1) / threads_per_block);
  KernelProgress progress;
  SHADOWCTS_LAUNCH(bruteforce_hard_shadow, block_count, threads_per_block, 0)
  (positions.data(), receivers.data(), receiver_triangles.data(),
   static_cast<std::uint32_t>(sample_count), casters.data(), caster_count, input.directional_light,
   input.light, states.data(), pair_tests.data(), progress.counter());
  progress.wait("bruteforce_hard_shadow", block_count);

  states.download(result.shadowed.data());
  unsigned long long total_tests = 0;
  pair_tests.download(&total_tests);
  result.pair_tests = total_tests;
  return result;
}

}  // namespace bruteforce
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
