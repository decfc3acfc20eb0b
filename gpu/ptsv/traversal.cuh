#pragma once
// Traversal of the shadow volumes through the cluster hierarchy on the device (the reference's
// traversal.h and two_pass.h define it: Sintorn 2014, Algorithm 1).
//
// The reference processes volumes one after another and shares the child masks: a trivially
// accepted child is cleared and no later volume tests it. Whether volume v tests child c of node n
// therefore depends only on the visits to n by earlier volumes, and every volume visits n at most
// once. So the device runs the traversal level by level over a global queue of (node, volume)
// jobs sorted by node, then volume (the simd port's schedule, simd/ptsv/traversal.h):
// - a warp per job tests the node's 32 children against the volume, one child per lane, and
//   __ballot_sync gathers the accept / refine / reject / cull masks (Algorithm 1, lines 7-19),
//   against the node's mask at the start of the level;
// - the mask each job really sees is the start mask less the accepts of the node's earlier jobs:
//   an exclusive OR-scan of the accepts segmented by node (Thrust), which is the reference's
//   ATOMICAND (line 24) in volume order; the counters follow from it exactly;
// - the refined children become the next level's jobs: counted, scanned into offsets, written,
//   and stable-sorted by child, so that each child's jobs stay in volume order;
// - at the leaves one warp per job tests the samples of the cluster's 8x8 tile (TESTVIEWSAMPLES)
//   and sets the shadow bits of those the volume and the receiver half-space rule shadow with
//   atomicOr (test-and-set).
// Two-pass (Section 2.2): the jobs the first pass would emit at the job level are this queue's
// jobs of that level, and the second pass finishes them in the reference's order per node, so the
// counters are the reference's; nothing depends on the order in which warps run.
#include <cstdint>
#include <vector>

#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>
#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>

#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "gpu/ptsv/device_memory.cuh"
#include "gpu/ptsv/hierarchy.cuh"
#include "gpu/ptsv/node_test.cuh"
#include "gpu/ptsv/ptsv_kernels.h"
#include "reference/ptsv/counters.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv {

struct TraversalParams {
  Layout layout;
  const double* slice_start;
  const Volume* volumes;
  Tolerances tolerances;
  bool implicit_cells;
  bool extra_planes;
};

// Each warp takes a run of consecutive jobs: the kernels' fixed cost (a launch's warps, the
// emulator's fibers) is paid once per run, and a leaf's tile is read by consecutive jobs of the
// same leaf.
constexpr std::uint32_t jobs_per_warp = 8;

inline std::size_t warp_threads(std::uint32_t jobs) {
  return std::size_t((jobs + jobs_per_warp - 1) / jobs_per_warp) * 32;
}

// Child verdicts of each job (bit j: child j of the node).
struct JobVerdicts {
  std::uint32_t* start;  // the node's mask at the start of the level
  std::uint32_t* accept;
  std::uint32_t* refine;
  std::uint32_t* reject;
  std::uint32_t* cull;
};

// TRAVERSENODE, one job at a time per warp: lane j tests child j if the node's mask still holds it
// (verdict codes: reject 0, accept 1, refine 2, cull 3).
__global__ void test_children(const std::uint32_t* job_node, const std::uint32_t* job_volume,
                              std::uint32_t jobs, int level, const std::uint32_t* live,
                              const std::uint32_t* child_mask, const std::uint32_t* first_child,
                              const std::uint32_t* child_index, const NodeBox* child_box,
                              TraversalParams params, JobVerdicts out,
                              unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  const std::uint32_t warp = (blockIdx.x * blockDim.x + threadIdx.x) / 32;
  const std::uint32_t lane = threadIdx.x % 32;
  const std::uint32_t first = warp * jobs_per_warp;
  const std::uint32_t last = first + jobs_per_warp < jobs ? first + jobs_per_warp : jobs;
  for (std::uint32_t job = first; job < last; ++job) {  // warp-uniform
    const std::uint32_t node = job_node[job];
    const std::uint32_t start = live[node];
    if (start == 0) {  // every child accepted by earlier volumes: nothing to test
      if (lane == 0)
        out.start[job] = out.accept[job] = out.refine[job] = out.reject[job] = out.cull[job] = 0;
      continue;
    }
    const bool has = ((start >> lane) & 1u) != 0;
    std::uint32_t verdict = verdict_reject;
    if (has) {
      const std::uint32_t child =
          first_child[node] + bit_count(child_mask[node] & ((1u << lane) - 1u));
      const Volume& volume = params.volumes[job_volume[job]];
      const int culling = params.extra_planes ? volume.extra_count : 0;
      const double reach = child_box[child].reach;
      if (params.implicit_cells) {
        const CellCorners corners =
            implicit_cell_corners(params.layout, params.slice_start, level + 1, child_index[child]);
        verdict = classify_node(volume, corners, reach, params.tolerances, culling);
      } else {
        verdict = classify_node(volume, child_box[child], reach, params.tolerances, culling);
      }
    }
    // The four verdicts are two bits: two ballots gather them (lanes without a child vote 0).
    const std::uint32_t low = __ballot_sync(0xffffffffu, (verdict & 1u) != 0);
    const std::uint32_t high = __ballot_sync(0xffffffffu, (verdict & 2u) != 0);
    if (lane == 0) {
      out.start[job] = start;
      out.accept[job] = low & ~high;
      out.refine[job] = ~low & high;
      out.reject[job] = start & ~low & ~high;
      out.cull[job] = low & high;
    }
  }
}

struct JobCounts {
  std::uint32_t* tests;
  std::uint32_t* accepts;
  std::uint32_t* rejects;
  std::uint32_t* culls;
  std::uint32_t* remaining;  // refined children still in the node's mask
  std::uint32_t* children;   // their number
};

// prior[job]: the accepts of the node's earlier jobs (exclusive OR-scan by node).
__global__ void apply_jobs(const std::uint32_t* job_node, std::uint32_t jobs, JobVerdicts v,
                           const std::uint32_t* prior, std::uint32_t* live, JobCounts out) {
  const std::uint32_t job = blockIdx.x * blockDim.x + threadIdx.x;
  if (job >= jobs) return;
  const std::uint32_t mask = v.start[job] & ~prior[job];
  const std::uint32_t accept = v.accept[job];
  out.tests[job] = bit_count(mask);
  out.accepts[job] = bit_count(accept & mask);
  out.rejects[job] = bit_count(v.reject[job] & mask);
  out.culls[job] = bit_count(v.cull[job] & mask);
  const std::uint32_t remaining = v.refine[job] & mask;
  out.remaining[job] = remaining;
  out.children[job] = bit_count(remaining);
  const std::uint32_t node = job_node[job];
  // The node's last job leaves the mask for the later levels' final pass.
  if (job + 1 == jobs || job_node[job + 1] != node) live[node] = mask & ~accept;
}

// The next level's jobs, children in bit order (the sort by child comes after).
__global__ void emit_jobs(const std::uint32_t* job_node, const std::uint32_t* job_volume,
                          std::uint32_t jobs, const std::uint32_t* remaining,
                          const std::uint32_t* offset, const std::uint32_t* child_mask,
                          const std::uint32_t* first_child, std::uint32_t* next_node,
                          std::uint32_t* next_volume) {
  const std::uint32_t job = blockIdx.x * blockDim.x + threadIdx.x;
  if (job >= jobs) return;
  const std::uint32_t node = job_node[job];
  const std::uint32_t mask = child_mask[node];
  std::uint32_t at = offset[job];
  for (std::uint32_t bits = remaining[job]; bits != 0; bits &= bits - 1) {
    const std::uint32_t lowest = bits & (~bits + 1u);
    next_node[at] = first_child[node] + bit_count(mask & (lowest - 1u));
    next_volume[at] = job_volume[job];
    ++at;
  }
}

struct SampleData {
  const gpu_ptsv::Sample* samples;
  const geometry::ReceiverHalfSpace* half_spaces;
  const std::uint32_t* tile_offsets;  // CSR over 8x8 tiles, row-major
  const std::uint32_t* tile_samples;  // regular samples in index order
};

// TESTVIEWSAMPLES, one job at a time per warp: every sample of the leaf's tile, a lane each.
__global__ void test_samples(const std::uint32_t* job_node, const std::uint32_t* job_volume,
                             std::uint32_t jobs, const std::uint32_t* leaf_index,
                             TraversalParams params, SampleData data, std::uint32_t* shadow_bits,
                             std::uint32_t* sample_tests, unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  const std::uint32_t warp = (blockIdx.x * blockDim.x + threadIdx.x) / 32;
  const std::uint32_t lane = threadIdx.x % 32;
  const std::uint32_t first = warp * jobs_per_warp;
  const std::uint32_t last = first + jobs_per_warp < jobs ? first + jobs_per_warp : jobs;
  for (std::uint32_t job = first; job < last; ++job) {
    std::uint32_t tx = 0, ty = 0, slice = 0;
    deinterleave(params.layout, leaf_index[job_node[job]], tx, ty, slice);
    const std::uint32_t tile = ty * params.layout.tiles_x + tx;
    const std::uint32_t begin = data.tile_offsets[tile], end = data.tile_offsets[tile + 1];
    if (lane == 0) sample_tests[job] = end - begin;
    const Volume& volume = params.volumes[job_volume[job]];
    for (std::uint32_t i = begin + lane; i < end; i += 32) {
      const std::uint32_t s = data.tile_samples[i];
      const gpu_ptsv::Sample sample = data.samples[s];
      const glm::dvec3 p(sample.position[0], sample.position[1], sample.position[2]);
      if (!sample_in_volume(volume, sample.receiver, p)) continue;
      std::uint32_t* word = shadow_bits + s / 32;
      const std::uint32_t bit = 1u << (s % 32);
      if ((atomicOr(word, 0u) & bit) != 0) continue;  // already shadowed: skip the rule
      const float* t = volume.caster;
      if (geometry::caster_counts(data.half_spaces[sample.half_space], p,
                                  glm::dvec3(t[0], t[1], t[2]), glm::dvec3(t[3], t[4], t[5]),
                                  glm::dvec3(t[6], t[7], t[8])))
        atomicOr(word, bit);
    }
  }
}

// The final pass: a node is intact while every bit on its path from the root is still set.
__global__ void intact_nodes(const std::uint32_t* parent, const std::uint32_t* index,
                             std::uint32_t count, const std::uint32_t* parent_live,
                             const std::uint8_t* parent_intact, std::uint8_t* intact) {
  const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c >= count) return;
  const std::uint32_t p = parent[c];
  intact[c] = parent_intact[p] != 0 && ((parent_live[p] >> (index[c] & 31u)) & 1u) != 0 ? 1 : 0;
}

// Samples in a trivially accepted node are shadowed.
__global__ void mark_accepted(const std::uint32_t* leaf_node_of,
                              const std::uint32_t* sorted_samples, std::uint32_t n,
                              const std::uint8_t* leaf_intact, std::uint32_t* shadow_bits) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  if (leaf_intact[leaf_node_of[i] - 1] != 0) return;
  const std::uint32_t s = sorted_samples[i];
  atomicOr(shadow_bits + s / 32, 1u << (s % 32));
}

inline std::uint64_t sum(const DeviceArray<std::uint32_t>& a, std::uint32_t count) {
  return thrust::reduce(thrust::device, a.data(), a.data() + count, std::uint64_t{0});
}

// Every volume through the hierarchy, then the final pass. live: per level, the child masks
// (cleared as the reference clears them).
inline void traverse(DeviceHierarchy& h, std::vector<DeviceArray<std::uint32_t>>& live,
                     const TraversalParams& params, const SampleData& data,
                     std::uint32_t volume_count, int job_level, std::uint32_t* shadow_bits,
                     ::shadowcts::ptsv::TraversalCounters& counters, LaunchCount& launches) {
  const int leaves = int(h.levels.size()) - 1;
  // Level 0: every volume visits the root, in volume order.
  DeviceArray<std::uint32_t> job_node(volume_count), job_volume(volume_count);
  job_node.zero();
  if (volume_count != 0)
    thrust::sequence(thrust::device, job_volume.data(), job_volume.data() + volume_count);
  std::uint32_t jobs = volume_count;
  KernelProgress progress;
  for (int l = 0; l <= leaves && jobs != 0; ++l) {
    DeviceLevel& level = h.levels[std::size_t(l)];
    counters.nodes_visited += jobs;
    if (l == job_level) {
      counters.first_pass_jobs += jobs;
      counters.second_pass_jobs += jobs;
    }
    if (l == leaves) {
      DeviceArray<std::uint32_t> tests(jobs);
      const unsigned blocks = launches.blocks(warp_threads(jobs));
      SHADOWCTS_LAUNCH(test_samples, blocks, threads_per_block, 0)
      (job_node.data(), job_volume.data(), jobs, level.index.data(), params, data, shadow_bits,
       tests.data(), progress.counter());
      progress.wait("test_samples", blocks);
      counters.sample_tests += sum(tests, jobs);
      break;
    }
    DeviceLevel& below = h.levels[std::size_t(l) + 1];
    DeviceArray<std::uint32_t> start(jobs), accept(jobs), refine(jobs), reject(jobs), cull(jobs);
    const JobVerdicts verdicts{start.data(), accept.data(), refine.data(), reject.data(),
                               cull.data()};
    const unsigned blocks = launches.blocks(warp_threads(jobs));
    SHADOWCTS_LAUNCH(test_children, blocks, threads_per_block, 0)
    (job_node.data(), job_volume.data(), jobs, l, live[std::size_t(l)].data(),
     level.child_mask.data(), level.first_child.data(), below.index.data(), below.box.data(),
     params, verdicts, progress.counter());
    progress.wait("test_children", blocks);
    DeviceArray<std::uint32_t> prior(jobs);
    thrust::exclusive_scan_by_key(
        thrust::device, job_node.data(), job_node.data() + jobs, accept.data(), prior.data(), 0u,
        thrust::equal_to<std::uint32_t>(), thrust::bit_or<std::uint32_t>());
    DeviceArray<std::uint32_t> tests(jobs), accepts(jobs), rejects(jobs), culls(jobs),
        remaining(jobs), children(jobs + 1);
    const JobCounts job_counts{tests.data(), accepts.data(),   rejects.data(),
                               culls.data(), remaining.data(), children.data()};
    SHADOWCTS_LAUNCH(apply_jobs, launches.blocks(jobs), threads_per_block, 0)
    (job_node.data(), jobs, verdicts, prior.data(), live[std::size_t(l)].data(), job_counts);
    after_launch("apply_jobs");
    counters.node_tests += sum(tests, jobs);
    counters.trivial_accepts += sum(accepts, jobs);
    counters.trivial_rejects += sum(rejects, jobs);
    counters.culling_plane_rejects += sum(culls, jobs);
    // Offsets of each job's children in the next queue.
    children.set(jobs, 0u);
    thrust::exclusive_scan(thrust::device, children.data(), children.data() + jobs + 1,
                           children.data());
    const std::uint32_t next_jobs = children.at(jobs);
    DeviceArray<std::uint32_t> next_node(next_jobs), next_volume(next_jobs);
    if (next_jobs != 0) {
      SHADOWCTS_LAUNCH(emit_jobs, launches.blocks(jobs), threads_per_block, 0)
      (job_node.data(), job_volume.data(), jobs, remaining.data(), children.data(),
       level.child_mask.data(), level.first_child.data(), next_node.data(), next_volume.data());
      after_launch("emit_jobs");
      // Jobs come in (parent, volume) order: a stable sort by child keeps each child's in volume
      // order.
      thrust::stable_sort_by_key(thrust::device, next_node.data(), next_node.data() + next_jobs,
                                 next_volume.data());
    }
    job_node = std::move(next_node);
    job_volume = std::move(next_volume);
    jobs = next_jobs;
  }

  // The final pass: samples below a cleared bit lie in a trivially accepted node.
  DeviceArray<std::uint8_t> intact(1);
  intact.set(0, std::uint8_t{1});
  for (int l = 1; l <= leaves; ++l) {
    DeviceLevel& level = h.levels[std::size_t(l)];
    DeviceArray<std::uint8_t> next(level.count);
    if (level.count != 0) {
      SHADOWCTS_LAUNCH(intact_nodes, launches.blocks(level.count), threads_per_block, 0)
      (level.parent.data(), level.index.data(), level.count, live[std::size_t(l) - 1].data(),
       intact.data(), next.data());
      after_launch("intact_nodes");
    }
    intact = std::move(next);
  }
  if (h.regular != 0) {
    SHADOWCTS_LAUNCH(mark_accepted, launches.blocks(h.regular), threads_per_block, 0)
    (h.levels[std::size_t(leaves)].node_of.data(), h.sorted_samples.data(), h.regular,
     intact.data(), shadow_bits);
    after_launch("mark_accepted");
  }
}

}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE::ptsv
