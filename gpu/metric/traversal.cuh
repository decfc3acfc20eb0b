#pragma once
// The per-sample traversal of the `metric` ternary metric tree (Deves et al. 2018, section 5.4),
// written once (gpu/emulator/kernel.h): nvcc builds it into the `cuda` backend, the host compiler
// into `cuda-emu` against the emulator. One thread per regular view sample walks the tree
// depth-first with a fixed-capacity stack, in the reference's order (reference/metric/traversal.h:
// overlap, far, near pushed, so near is walked first), so its counters are the reference's.
//
// Exactness: the walk's decisions compare doubles the reference computes with std::atan2 and
// glm, which a device (its own atan2, fused multiply-adds) rounds differently by a few ulp. The
// kernel therefore decides a comparison only where its value lies outside a window around the
// threshold (2^-40 of an angle, or of S for lengths: far above a few ulp of numbers below 8), and
// otherwise hands the whole sample to the host, which walks it with the reference's own code. The
// triangles are decided by the shared decide_caster (shadowcts/geometry/caster_blocks_sample.h),
// whose float test and exact predicates give the same bits on host and device; the one step it
// leaves to the host here is the exact segment test of a float miss beside an edge (about 0.1 %
// of the samples on the default fixtures), whose expansions would cost every thread's stack.
// A sample's counters are those of its own walk, so the sums are the reference's whichever side
// walks it.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gpu/device_array.cuh"
#include "gpu/emulator/kernel.h"
#include "gpu/kernel_progress.cuh"
#include "gpu/metric/traversal.h"
#include "shadowcts/geometry/caster_blocks_sample.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace metric {

using gpu_metric::MetricCluster;
using gpu_metric::MetricFrame;
using gpu_metric::MetricNode;
using gpu_metric::MetricReceiver;
using gpu_metric::MetricTriangle;
using gpu_metric::PivotKind;

using gpu_metric::threads_per_block;

// The exact receiver half-space rule inlined into the walk would make every thread pay its
// registers and stack (see gpu/bruteforce); out of line, only the cluster tests do.
#if SHADOWCTS_EMULATED
#define SHADOWCTS_METRIC_OUT_OF_LINE
#define SHADOWCTS_METRIC_LAUNCH_BOUNDS
#else
#define SHADOWCTS_METRIC_OUT_OF_LINE __noinline__
#define SHADOWCTS_METRIC_LAUNCH_BOUNDS __launch_bounds__(threads_per_block)
#endif

// The sample's receiver half-space, built on first need (decide_caster calls it only once
// a triangle may block).
struct SampleHalfSpace {
  const MetricReceiver* receiver;
  bool directional;
  glm::dvec3 light;
  geometry::ReceiverHalfSpace half_space;
  bool built;

  SHADOWCTS_HD const geometry::ReceiverHalfSpace& operator()() {
    if (!built) {
      const MetricReceiver r = *receiver;
      // No receiver: no plane, every caster counts (the reference's sample_half_space).
      if (r.present != 0)
        half_space = geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1),
                                                   glm::dvec3(r.v2), directional, light);
      built = true;
    }
    return half_space;
  }
};

// a <= b where the answer is certain; `unsure` is set where a and b are within `window` (finite
// values only: infinities come from the host or from covers_everything and are exact).
__device__ inline bool certain_le(double a, double b, double window, bool& unsure) {
  if (std::isfinite(a) && std::isfinite(b) && std::fabs(a - b) <= window) unsure = true;
  return a <= b;
}

__device__ inline double angle_between(const glm::dvec3& u, const glm::dvec3& v) {
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

// The reference's distance_to_arc (reference/metric/angular_distance.h). Where the branch of the
// two formulas flips, both give the same angle up to rounding: the distance is continuous.
__device__ inline double distance_to_arc(const glm::dvec3& u, const MetricNode& node) {
  const double height = glm::dot(u, node.arc_normal);
  const glm::dvec3 in_plane = u - height * node.arc_normal;
  const double in_plane_length = glm::length(in_plane);
  if (in_plane_length > 0.0 && glm::dot(glm::cross(node.a, in_plane), node.arc_normal) >= 0.0 &&
      glm::dot(glm::cross(in_plane, node.b), node.arc_normal) >= 0.0)
    return std::atan2(std::fabs(height), in_plane_length);
  const double to_a = angle_between(u, node.a), to_b = angle_between(u, node.b);
  return to_a < to_b ? to_a : to_b;
}

// The reference's distance to a segment in the plane (light_space_elements.cpp).
__device__ inline double distance_to_segment(const glm::dvec3& p, const glm::dvec3& a,
                                             const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length_squared = glm::dot(ab, ab);
  double t = length_squared > 0.0 ? glm::dot(p - a, ab) / length_squared : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return glm::length(p - (a + t * ab));
}

// The reference's pivot_distance, up to rounding.
__device__ inline double pivot_distance(const MetricNode& node, const glm::dvec3& query) {
  switch (node.kind) {
    case PivotKind::point_cone:
      return angle_between(query, node.a) - node.radius;
    case PivotKind::arc_cone:
      return distance_to_arc(query, node) - node.radius;
    case PivotKind::disk:
      return glm::length(query - node.a) - node.radius;
    case PivotKind::capsule_2d:
      return distance_to_segment(query, node.a, node.b) - node.radius;
    case PivotKind::covers_everything:
      break;
  }
  return -INFINITY;
}

struct WalkCounters {
  std::uint32_t nodes_visited = 0, clusters_without_hit = 0, triangle_tests = 0;
};

// Section 5.4, step 2 and the triangles of one candidate cluster: the slabs, then the shared
// triangle decision with an early exit on the first blocker. Returns sample_shadowed, sample_lit
// (no blocker), sample_unsure (a slab decision within its window) or sample_exact_test.
SHADOWCTS_METRIC_OUT_OF_LINE __device__ std::uint8_t test_cluster(
    const MetricCluster& cluster, const MetricTriangle* triangles, const MetricFrame& frame,
    const glm::dvec3& p, const glm::dvec3& segment_end, const RaySpace& ray_space,
    std::uint32_t receiver, SampleHalfSpace& half_space, WalkCounters& counters) {
  const double s_from = glm::dot(cluster.slab_normal, p);
  const double s_to = glm::dot(cluster.slab_normal, segment_end);
  bool unsure = false;
  const bool meets =
      certain_le(cluster.slab_low, s_from > s_to ? s_from : s_to, frame.length_window, unsure) &&
      certain_le(s_from < s_to ? s_from : s_to, cluster.slab_high, frame.length_window, unsure);
  if (unsure) return gpu_metric::sample_unsure;
  if (!meets) return gpu_metric::sample_lit;
  for (std::uint32_t k = cluster.begin; k < cluster.end; ++k) {
    const MetricTriangle t = triangles[k];
    if (t.triangle == receiver) continue;  // the receiver never shadows its own sample
    ++counters.triangle_tests;
    const geometry::CasterDecision decision = geometry::decide_caster<false>(
        ray_space, p, frame.directional, frame.light_exact, t.v0, t.v1, t.v2, half_space);
    if (decision == geometry::CasterDecision::blocks) return gpu_metric::sample_shadowed;
    if (decision == geometry::CasterDecision::needs_exact_segment_test)
      return gpu_metric::sample_exact_test;
  }
  ++counters.clusters_without_hit;
  return gpu_metric::sample_lit;
}

// One sample's walk (the reference's sample_is_shadowed and for_each_candidate_element).
__device__ std::uint8_t walk(const MetricNode* nodes, std::uint32_t node_count,
                             const MetricCluster* clusters, const MetricTriangle* triangles,
                             const MetricFrame& frame, const glm::vec3& position,
                             std::uint32_t receiver, const MetricReceiver* receiver_triangle,
                             std::uint32_t stack_limit, WalkCounters& counters) {
  const glm::dvec3 p(position);
  glm::dvec3 query(0.0);
  double light_distance = 0.0;
  if (frame.directional) {
    query = glm::dvec3(glm::dot(p, frame.plane_x), glm::dot(p, frame.plane_y), 0.0);
    light_distance = -glm::dot(p, frame.towards_light);
  } else {
    const glm::dvec3 from_light = p - frame.light_position;
    light_distance = glm::length(from_light);
    // Exactly zero in any rounding: the sample is the light, the segment a point.
    if (!(light_distance > 0.0)) return gpu_metric::sample_lit;
    query = from_light / light_distance;
  }
  if (node_count == 0) return gpu_metric::sample_lit;
  const RaySpace ray_space =
      make_ray_space(frame.directional ? ray_to_directional_light(position, frame.light_float)
                                       : segment_to_point_light(position, frame.light_float));
  const glm::dvec3 segment_end =
      frame.directional ? p + frame.ray_length * frame.towards_light : frame.light_position;
  const double pivot_window = frame.directional ? frame.length_window : frame.angle_window;
  SampleHalfSpace half_space{receiver_triangle, frame.directional, frame.light_exact, {}, false};

  std::uint32_t stack[gpu_metric::stack_capacity];
  std::uint32_t size = 0;
  stack[size++] = 0;
  bool unsure = false;
  while (size > 0) {
    const MetricNode& node = nodes[stack[--size]];
    ++counters.nodes_visited;
    // Step 1: the sample is closer to the light than everything in the subtree.
    const bool reaches =
        certain_le(node.light_distance, light_distance, frame.length_window, unsure);
    if (unsure) return gpu_metric::sample_unsure;
    if (!reaches) continue;
    const double distance = pivot_distance(node, query);
    // Step 2: inside the pivot's cone and not in front of it, its cluster may block.
    const bool inside = certain_le(distance, 0.0, pivot_window, unsure);
    if (unsure) return gpu_metric::sample_unsure;
    if (inside) {
      const bool behind =
          certain_le(node.pivot_light_distance, light_distance, frame.length_window, unsure);
      if (unsure) return gpu_metric::sample_unsure;
      if (behind) {
        const std::uint8_t state =
            test_cluster(clusters[node.cluster], triangles, frame, p, segment_end, ray_space,
                         receiver, half_space, counters);
        if (state != gpu_metric::sample_lit) return state;
      }
    }
    // Step 3: the overlap child inside its interval, near and far by delta (thresholds with the
    // reference's slack, computed on the host).
    const std::uint32_t overlap = node.child[2], far = node.child[1], near = node.child[0];
    const bool take_overlap = overlap != gpu_metric::no_node &&
                              certain_le(node.overlap_low, distance, pivot_window, unsure) &&
                              certain_le(distance, node.overlap_high, pivot_window, unsure);
    const bool take_far =
        far != gpu_metric::no_node && certain_le(node.far_side, distance, pivot_window, unsure);
    const bool take_near =
        near != gpu_metric::no_node && certain_le(distance, node.near_side, pivot_window, unsure);
    if (unsure) return gpu_metric::sample_unsure;
    // Never a silent overflow: the host walks such a sample (and counts it).
    if (size + std::uint32_t(take_overlap) + std::uint32_t(take_far) + std::uint32_t(take_near) >
        stack_limit)
      return gpu_metric::sample_stack_overflow;
    if (take_overlap) stack[size++] = overlap;
    if (take_far) stack[size++] = far;
    if (take_near) stack[size++] = near;
  }
  return gpu_metric::sample_lit;
}

__global__ void SHADOWCTS_METRIC_LAUNCH_BOUNDS metric_traversal(
    const MetricNode* nodes, std::uint32_t node_count, const MetricCluster* clusters,
    const MetricTriangle* triangles, MetricFrame frame, const glm::vec3* sample_positions,
    const std::uint32_t* sample_receivers, const MetricReceiver* sample_receiver_triangles,
    std::uint32_t sample_count, std::uint32_t stack_limit, std::uint8_t* sample_states,
    std::uint32_t* sample_counters, unsigned long long* totals,
    unsigned long long* blocks_started) {
  count_started_block(blocks_started);
  const std::uint32_t sample = blockIdx.x * blockDim.x + threadIdx.x;
  WalkCounters counters;
  if (sample < sample_count) {
    const std::uint8_t state =
        walk(nodes, node_count, clusters, triangles, frame, sample_positions[sample],
             sample_receivers[sample], sample_receiver_triangles + sample, stack_limit, counters);
    sample_states[sample] = state;
    // A sample handed to the host is counted there, by the reference's walk.
    if (gpu_metric::handed_to_host(state)) counters = WalkCounters{};
    sample_counters[sample] = counters.nodes_visited;
    sample_counters[sample_count + sample] = counters.clusters_without_hit;
    sample_counters[2 * std::size_t(sample_count) + sample] = counters.triangle_tests;
  }
  // Integer sums are order-independent, so the totals are deterministic. Every lane of the block
  // gets here (no early return), as the full-mask shuffles require.
  unsigned long long sums[3] = {counters.nodes_visited, counters.clusters_without_hit,
                                counters.triangle_tests};
  for (int k = 0; k < 3; ++k) {
    for (int offset = warpSize / 2; offset > 0; offset /= 2)
      sums[k] += __shfl_down_sync(0xffffffffu, sums[k], offset);
    if (threadIdx.x % warpSize == 0 && sums[k] != 0) atomicAdd(totals + k, sums[k]);
  }
}

// Takes the input by value: each host array is freed once uploaded.
inline gpu_metric::MetricResult run(gpu_metric::MetricInput input) {
  const std::size_t sample_count = input.sample_positions.size();
  gpu_metric::MetricResult result;
  result.state.assign(sample_count, gpu_metric::sample_lit);
  if (sample_count == 0) return result;
  if (sample_count > UINT32_MAX || input.nodes.size() > UINT32_MAX ||
      input.triangles.size() > UINT32_MAX)
    throw std::length_error("metric_traversal: more than 2^32 samples, nodes or triangles");
  // At least the root's entry.
  const std::uint32_t stack_limit = input.stack_limit < 1 ? 1
                                    : input.stack_limit < gpu_metric::stack_capacity
                                        ? input.stack_limit
                                        : gpu_metric::stack_capacity;
  if (input.sample_receivers.size() != sample_count ||
      input.sample_receiver_triangles.size() != sample_count)
    throw std::invalid_argument("metric_traversal: one receiver and receiver triangle per sample");

  const auto node_count = static_cast<std::uint32_t>(input.nodes.size());
  const DeviceArray<MetricNode> nodes = upload_and_free(input.nodes);
  const DeviceArray<MetricCluster> clusters = upload_and_free(input.clusters);
  const DeviceArray<MetricTriangle> triangles = upload_and_free(input.triangles);
  const DeviceArray<glm::vec3> positions = upload_and_free(input.sample_positions);
  const DeviceArray<std::uint32_t> receivers = upload_and_free(input.sample_receivers);
  const DeviceArray<MetricReceiver> receiver_triangles =
      upload_and_free(input.sample_receiver_triangles);
  DeviceArray<std::uint8_t> states(sample_count);
  DeviceArray<std::uint32_t> sample_counters(3 * sample_count);
  DeviceArray<unsigned long long> totals(3);
  totals.zero();

  const auto block_count =
      static_cast<unsigned>((sample_count + threads_per_block - 1) / threads_per_block);
  KernelProgress progress;
  SHADOWCTS_LAUNCH(metric_traversal, block_count, threads_per_block, 0)
  (nodes.data(), node_count, clusters.data(), triangles.data(), input.frame, positions.data(),
   receivers.data(), receiver_triangles.data(), static_cast<std::uint32_t>(sample_count),
   stack_limit, states.data(), sample_counters.data(), totals.data(), progress.counter());
  progress.wait("metric_traversal", block_count);

  states.download(result.state.data());
  std::vector<std::uint32_t> per_sample(3 * sample_count);
  sample_counters.download(per_sample.data());
  const auto part = [&](std::size_t k) {
    return std::vector<std::uint32_t>(per_sample.begin() + std::ptrdiff_t(k * sample_count),
                                      per_sample.begin() + std::ptrdiff_t((k + 1) * sample_count));
  };
  result.sample_nodes_visited = part(0);
  result.sample_clusters_tested_without_hit = part(1);
  result.sample_triangle_tests = part(2);
  unsigned long long sums[3] = {0, 0, 0};
  totals.download(sums);
  result.nodes_visited = sums[0];
  result.clusters_tested_without_hit = sums[1];
  result.triangle_tests = sums[2];
  return result;
}

}  // namespace metric
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
