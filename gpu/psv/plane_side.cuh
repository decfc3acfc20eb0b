#pragma once
// The side of a query point against a node's plane (reference/psv/plane_side.h): the float plane
// answers where its value clears the shared filter's bound (shadowcts/geometry/plane_filter.h, the
// reference's own arithmetic), and the exact orientation of the triangle's vertices otherwise.
// Both decide the exact cases with the shared expansion-based predicate
// (shadowcts/geometry/exact_orientation.h), so the tree is searched along the same path.
#include <cstdint>

#include <glm/vec3.hpp>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/psv_kernels.h"
#include "gpu/psv/top_tree.cuh"
#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/plane_filter.h"

// The exact fallback's expansions take hundreds of registers where inlined, for a path few tests
// take: out of line on the device (as the brute-force kernel keeps its exact rule).
#if SHADOWCTS_EMULATED
#define SHADOWCTS_PSV_OUT_OF_LINE
#else
#define SHADOWCTS_PSV_OUT_OF_LINE __noinline__
#endif

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

struct PlaneSide {
  const PsvDeviceNode* nodes;
  const PsvDeviceSource* sources;
  const PsvDeviceTriangle* triangles;
  bool directional;
  glm::dvec3 light;  // position, or direction towards the light
  geometry::PlaneFilter filter;
};

__device__ inline glm::dvec3 triangle_vertex(const PsvDeviceTriangle& t, int i) {
  return glm::dvec3(i == 0 ? t.v0 : (i == 1 ? t.v1 : t.v2));
}

// Exact sign of the plane of `node` at p from its triangle (reference PlaneSide::exact_side).
SHADOWCTS_PSV_OUT_OF_LINE __device__ int exact_side(const PlaneSide& planes, std::uint32_t node,
                                                    const glm::dvec3& p) {
  const PsvDeviceTriangle t = planes.triangles[volume_triangle(planes.nodes, node)];
  const PsvDeviceSource source = planes.sources[volume_of(node)];
  const std::uint32_t k = node % nodes_per_volume;
  // One call site per predicate: each inlines a large expansion evaluation.
  if (k != capping_plane && planes.directional) {
    // The sign of det[hi - lo, d, p - lo] = -det[hi - lo, p - lo, d].
    const glm::dvec3 lo = triangle_vertex(t, source.edge[k][0]);
    const glm::dvec3 hi = triangle_vertex(t, source.edge[k][1]);
    return -source.orientation[k] * geometry::orientation_towards(lo, hi, p, planes.light);
  }
  // Capping plane: the triangle's own; edge plane of a point light: through L, lo and hi.
  const bool capping = k == capping_plane;
  const glm::dvec3 a = capping ? triangle_vertex(t, 0) : planes.light;
  const glm::dvec3 b = triangle_vertex(t, capping ? 1 : source.edge[k][0]);
  const glm::dvec3 c = triangle_vertex(t, capping ? 2 : source.edge[k][1]);
  const int sign = geometry::orientation(a, b, c, p);
  return source.orientation[k] * sign;
}

// Exact sign of the plane of `node` at p: 1 outside (positive side), 0 on it, -1 inside.
// `exact_tests` counts the tests the float filter left open.
__device__ inline int side(const PlaneSide& planes, std::uint32_t node, const glm::dvec3& p,
                           std::uint32_t& exact_tests) {
  const PsvDeviceNode& n = planes.nodes[node];
  const double v = geometry::plane_value(n.plane, p);
  const double bound =
      geometry::plane_error_bound(planes.filter, n.plane, is_capping_node(node), p);
  if (v > bound) return 1;
  if (v < -bound) return -1;
  ++exact_tests;
  return exact_side(planes, node, p);
}

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
