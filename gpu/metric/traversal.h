#pragma once
// Launch interface of the `metric` traversal kernel (traversal.cuh): one thread per regular view
// sample walks the reference's ternary metric tree (reference/metric/traversal.h). Plain data
// only, so that the C++20 host side and the C++17 CUDA translation unit share it.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/host_device.h"

namespace shadowcts::gpu_metric {

inline constexpr std::uint32_t no_node = 0xffffffffu;

// How a node's pivot measures a query (the reference's pivot_distance).
enum class PivotKind : std::uint8_t {
  point_cone,         // point light, point centre: angle to direction a
  arc_cone,           // point light, arc centre: angle to the great arc a -> b
  disk,               // directional light, point centre: distance to a in the plane
  capsule_2d,         // directional light, segment centre: distance to segment a b in the plane
  covers_everything,  // the light is inside the pivot's volume: -infinity
};

// One node of the reference's tree, in the reference's node order, with its pivot element's
// geometry and the reference's thresholds (computed on the host by the reference's expressions,
// so the kernel compares against the very same doubles).
struct MetricNode {
  double light_distance = 0.0;        // the subtree's smallest light distance (step 1)
  double pivot_light_distance = 0.0;  // the pivot element's (step 2)
  glm::dvec3 a{0.0}, b{0.0};          // the pivot's centre
  glm::dvec3 arc_normal{0.0};         // arc_cone: unit a x b
  double radius = 0.0;
  double overlap_low = 0.0, overlap_high = 0.0;          // overlap_min - slack, overlap_max + slack
  double far_side = 0.0, near_side = 0.0;                // delta - slack, delta + slack
  std::uint32_t child[3] = {no_node, no_node, no_node};  // near, far, overlap
  std::uint32_t pivot = 0;                               // element index
  std::uint32_t cluster = 0;                             // the pivot element's cluster
  PivotKind kind = PivotKind::point_cone;
};

// Per cluster: its slabs (enlarged by the margin, as the reference's segment_meets_slabs) and its
// triangles [begin, end) in MetricInput::triangles.
struct MetricCluster {
  glm::dvec3 slab_normal{0.0};
  double slab_low = 0.0, slab_high = 0.0;
  std::uint32_t begin = 0, end = 0;
};

struct MetricTriangle {
  glm::vec3 v0, v1, v2;
  std::uint32_t triangle;  // index into Case::triangles, to skip a sample's own receiver
};

struct MetricReceiver {
  glm::vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
  std::uint32_t present = 0;  // 0: no receiver (the rule is void)
};

struct MetricFrame {
  bool directional = false;
  glm::dvec3 light_position{0.0};         // point light
  glm::dvec3 towards_light{0.0};          // directional: unit
  glm::dvec3 plane_x{0.0}, plane_y{0.0};  // directional: the plane orthogonal to it
  double ray_length = 0.0;                // directional: the slab test's segment length
  glm::vec3 light_float{0.0f};            // L or d as the float ray takes it
  glm::dvec3 light_exact{0.0};            // L or d as the exact tests take it
  // Half-widths of the bands around a threshold where the kernel hands the sample to the host:
  // for angles (radians) and for lengths (in the plane, along the light, of the slab tests).
  double angle_window = 0.0, length_window = 0.0;
};

// Per-sample answers of the kernel.
inline constexpr std::uint8_t sample_lit = 0;
inline constexpr std::uint8_t sample_shadowed = 1;
// A decision of the walk lay within its window of a threshold: the host walks the sample with the
// reference's own code.
inline constexpr std::uint8_t sample_unsure = 2;
// The walk needed more than stack_capacity entries: the host walks the sample.
inline constexpr std::uint8_t sample_stack_overflow = 3;
// A float miss beside a triangle's edge needs the exact segment test (CasterDecision::
// needs_exact_segment_test): the host walks the sample.
inline constexpr std::uint8_t sample_exact_test = 4;

SHADOWCTS_HD inline bool handed_to_host(std::uint8_t state) {
  return state == sample_unsure || state == sample_stack_overflow || state == sample_exact_test;
}

// Threads per block of the traversal kernel.
inline constexpr int threads_per_block = 128;

// Entries of a thread's stack. The reference's walk holds at most 2 per level of the tree plus the
// children of the node just popped, so depth <= 62 never overflows (fixtures reach ~25).
inline constexpr std::uint32_t stack_capacity = 128;

struct MetricInput {
  MetricFrame frame;
  // Entries a thread may use, at most stack_capacity (tests lower it to exercise the hand-back).
  std::uint32_t stack_limit = stack_capacity;
  std::vector<MetricNode> nodes;  // nodes[0] is the root when not empty
  std::vector<MetricCluster> clusters;
  std::vector<MetricTriangle> triangles;  // cluster after cluster
  // Regular samples, in RegularSamples order.
  std::vector<glm::vec3> sample_positions;
  std::vector<std::uint32_t> sample_receivers;
  std::vector<MetricReceiver> sample_receiver_triangles;
};

struct MetricResult {
  std::vector<std::uint8_t> state;  // per sample, one of sample_*
  // The reference's traversal counters summed over the samples the kernel decided (integer sums:
  // independent of the order threads finish).
  std::uint64_t nodes_visited = 0;
  std::uint64_t clusters_tested_without_hit = 0;
  std::uint64_t triangle_tests = 0;
  // The same per sample (zero for a sample handed to the host): for diffs against the reference
  // and heat maps.
  std::vector<std::uint32_t> sample_nodes_visited;
  std::vector<std::uint32_t> sample_clusters_tested_without_hit;
  std::vector<std::uint32_t> sample_triangle_tests;
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
MetricResult run_metric_traversal_kernel(MetricInput input);

// The same kernel source run by the CUDA-subset emulator on the host (gpu/emulator).
MetricResult run_metric_traversal_kernel_emulated(MetricInput input);

}  // namespace shadowcts::gpu_metric
