#pragma once
// The psv query kernel, written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda`
// backend, the host compiler into `cuda-emu` against the emulator. One thread per regular view
// sample locates it in the uploaded TOP tree with the variant's query (PSV, D-PSV, D-Stackless,
// D-Hybrid), a fixed array of psv_max_stack_capacity nodes as its stack. A stack query that
// overflows is counted and answered by the stackless query (reference/psv/psv_shadows.h), so the
// mask is the tree's answer and every per-sample value equals the reference's.
//
// The queries only read the tree: no thread depends on another, so no barrier and no shared
// memory. Totals are integer sums and maxima: the same for any launch configuration and schedule.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "gpu/psv/psv_kernels.h"
#include "gpu/psv/query_context.cuh"
#include "gpu/psv/query_hybrid.cuh"
#include "gpu/psv/query_stack.cuh"
#include "gpu/psv/query_stackless.cuh"
#include "shadowcts/geometry/plane_filter.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

constexpr int threads_per_block = 128;

// Unbounded, ptxas gave the kernel 255 registers (sm_90; 40 KB cumulative stack, nearly all of it
// the receiver half-space rule's expansions): 8 resident warps per SM for a latency-bound
// traversal. Bounded to 8 blocks of 128 per SM (64 registers), as the brute-force kernel is; not
// yet measured on a device.
#if SHADOWCTS_EMULATED
#define SHADOWCTS_PSV_LAUNCH_BOUNDS
#else
#define SHADOWCTS_PSV_LAUNCH_BOUNDS __launch_bounds__(threads_per_block, 8)
#endif

// Slots of the totals the kernel adds up.
enum Total : int { total_overflows, total_switches, total_exact, total_count };
enum Maximum : int { maximum_high_water, maximum_count };

__global__ void SHADOWCTS_PSV_LAUNCH_BOUNDS
psv_query(QueryContext context, PsvDeviceQuery query, std::uint32_t stack_capacity,
          const glm::vec3* sample_positions, const std::uint32_t* sample_receivers,
          std::uint32_t sample_count, std::uint8_t* shadowed, std::uint32_t* nodes_visited,
          unsigned long long* totals, unsigned int* maxima, unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  const std::uint32_t sample = blockIdx.x * blockDim.x + threadIdx.x;
  if (sample >= sample_count) return;
  QueryWork work;
  unsigned long long overflowed = 0;
  QueryPoint p;
  p.position = glm::dvec3(sample_positions[sample]);
  p.receiver = sample_receivers[sample];
  p.light_depth =
      geometry::sample_light_depth(context.planes.directional, context.planes.light, p.position);
  std::uint32_t storage[psv_max_stack_capacity];
  NodeStack stack(storage, stack_capacity);
  QueryAnswer answer = QueryAnswer::lit;
  switch (query) {
    case PsvDeviceQuery::stack:
    case PsvDeviceQuery::depth:
      answer = query_stack(context, p, stack, work);
      if (answer == QueryAnswer::stack_overflow) {
        overflowed = 1;
        answer = query_stackless(context, p, work);
      }
      break;
    case PsvDeviceQuery::stackless:
      answer = query_stackless(context, p, work);
      break;
    case PsvDeviceQuery::hybrid:
      answer = query_hybrid(context, p, stack, work);
      break;
  }
  shadowed[sample] = answer == QueryAnswer::shadowed ? 1 : 0;
  nodes_visited[sample] = work.nodes_visited;

  // The node-visit total and maximum come from nodes_visited on the host. The other values are
  // zero for most samples: an atomic only where one is not (a warp reduction would cost every
  // lane five collectives, most of the emulated run time).
  if (overflowed != 0) atomicAdd(&totals[total_overflows], overflowed);
  if (work.hybrid_switches != 0)
    atomicAdd(&totals[total_switches], static_cast<unsigned long long>(work.hybrid_switches));
  if (work.exact_plane_tests != 0)
    atomicAdd(&totals[total_exact], static_cast<unsigned long long>(work.exact_plane_tests));
  if (work.stack_high_water != 0) atomicMax(&maxima[maximum_high_water], work.stack_high_water);
}

// Takes the input by value: each host array is freed once uploaded.
inline PsvQueryResult run(PsvQueryInput input) {
  const std::size_t sample_count = input.sample_positions.size();
  PsvQueryResult result;
  result.shadowed.assign(sample_count, 0);
  result.nodes_visited.assign(sample_count, 0);
  if (sample_count == 0) return result;
  if (sample_count > UINT32_MAX || input.nodes.size() >= UINT32_MAX) {
    throw std::length_error("psv query: more than 2^32 samples or tree nodes");
  }
  if (input.sample_receivers.size() != sample_count ||
      input.sources.size() * 4 != input.nodes.size() ||
      input.stack_capacity > psv_max_stack_capacity) {
    throw std::invalid_argument(
        "psv query: one receiver per sample, one source per volume, stack capacity <= 32");
  }

  const std::uint32_t root = input.nodes.empty() ? psv_no_node : input.root;
  const DeviceArray<PsvDeviceNode> nodes = upload_and_free(input.nodes);
  const DeviceArray<PsvDeviceSource> sources = upload_and_free(input.sources);
  const DeviceArray<PsvDeviceTriangle> triangles = upload_and_free(input.triangles);
  const DeviceArray<glm::vec3> positions = upload_and_free(input.sample_positions);
  const DeviceArray<std::uint32_t> receivers = upload_and_free(input.sample_receivers);
  DeviceArray<std::uint8_t> states(sample_count);
  DeviceArray<std::uint32_t> visited(sample_count);
  DeviceArray<unsigned long long> totals(total_count);
  DeviceArray<unsigned int> maxima(maximum_count);
  totals.zero();
  maxima.zero();

  QueryContext context;
  context.planes.nodes = nodes.data();
  context.planes.sources = sources.data();
  context.planes.triangles = triangles.data();
  context.planes.directional = input.directional_light;
  context.planes.light = input.light;
  context.planes.filter = input.filter;
  context.root = root;
  // The depth test belongs to D-PSV, D-Stackless and D-Hybrid; the paper's PSV has none.
  context.depth_test = input.query != PsvDeviceQuery::stack;

  const auto block_count =
      static_cast<unsigned>((sample_count + threads_per_block - 1) / threads_per_block);
  KernelProgress progress;
  SHADOWCTS_LAUNCH(psv_query, block_count, threads_per_block, 0)
  (context, input.query, input.stack_capacity, positions.data(), receivers.data(),
   static_cast<std::uint32_t>(sample_count), states.data(), visited.data(), totals.data(),
   maxima.data(), progress.counter());
  progress.wait("psv_query", block_count);

  states.download(result.shadowed.data());
  visited.download(result.nodes_visited.data());
  unsigned long long sums[total_count] = {};
  unsigned int most[maximum_count] = {};
  totals.download(sums);
  maxima.download(most);
  for (const std::uint32_t visits : result.nodes_visited) {
    result.nodes_visited_total += visits;
    if (visits > result.nodes_visited_max) result.nodes_visited_max = visits;
  }
  result.stack_overflows = sums[total_overflows];
  result.hybrid_switches = sums[total_switches];
  result.exact_plane_tests = sums[total_exact];
  result.stack_high_water = most[maximum_high_water];
  return result;
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
