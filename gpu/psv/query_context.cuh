#pragma once
// What the four TOP tree queries share (reference/psv/query_context.h): the point being located,
// its work record, the three tests each query makes at a node (plane side, depth test, whether the
// intersection child needs a visit) and the fixed-capacity stack of the stack and hybrid queries.
// Every decision is the reference's, evaluated with the same roundings.
#include <cstdint>

#include <glm/vec3.hpp>

#include "gpu/emulator/kernel.h"
#include "gpu/psv/plane_side.cuh"
#include "gpu/psv/psv_kernels.h"
#include "gpu/psv/top_tree.cuh"
#include "shadowcts/geometry/plane_filter.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/rounded_arithmetic.h"

namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE {
namespace psv {

struct QueryPoint {
  glm::dvec3 position{0.0};
  std::uint32_t receiver = psv_no_node;  // its triangle never shadows it
  double light_depth = 0.0;              // upper bound on its light distance
  // The receiver half-space rule of this point, built when the first volume containing it is
  // found (most points are in none).
  bool has_half_space = false;
  geometry::ReceiverHalfSpace half_space;
};

enum class QueryAnswer { lit, shadowed, stack_overflow };

struct QueryWork {
  std::uint32_t nodes_visited = 0;  // nodes whose plane or links the query read
  std::uint32_t stack_high_water = 0;
  std::uint32_t hybrid_switches = 0;
  std::uint32_t exact_plane_tests = 0;
};

// The rule of the point's receiver for a triangle whose volume holds it, out of line on the
// device: its exact expansion products need kilobytes of stack.
SHADOWCTS_PSV_OUT_OF_LINE __device__ bool caster_counts(const PlaneSide& planes,
                                                        std::uint32_t triangle, QueryPoint& p) {
  if (p.receiver == psv_no_node) return true;  // no receiver, no rule
  if (!p.has_half_space) {
    const PsvDeviceTriangle r = planes.triangles[p.receiver];
    p.half_space = geometry::receiver_half_space(
        glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2), planes.directional, planes.light);
    p.has_half_space = true;
  }
  const PsvDeviceTriangle t = planes.triangles[triangle];
  return geometry::caster_counts(p.half_space, p.position, glm::dvec3(t.v0), glm::dvec3(t.v1),
                                 glm::dvec3(t.v2));
}

struct QueryContext {
  PlaneSide planes;
  std::uint32_t root;
  bool depth_test;

  // > 0: continue in the positive child; otherwise the negative one. A capping node's negative
  // side holds p only when its triangle shadows p (not p's receiver, not rejected by the rule);
  // otherwise p counts as in front of it (reference QueryContext::location explains why).
  __device__ int location(std::uint32_t index, QueryPoint& p, QueryWork& work) const {
    if (!is_capping_node(index)) return side(planes, index, p.position, work.exact_plane_tests);
    const std::uint32_t triangle = volume_triangle(planes.nodes, index);
    if (triangle == p.receiver) return 1;
    const int s = side(planes, index, p.position, work.exact_plane_tests);
    if (s > 0 || caster_counts(planes, triangle, p)) return s;
    return 1;
  }

  // [depth] Mora 2016, section 3.3: true when p is closer to the light than every triangle of the
  // subtree of the volume that starts at `volume_first_node`.
  __device__ bool skipped_by_depth(std::uint32_t volume_first_node, const QueryPoint& p) const {
    return depth_test && p.light_depth < double(volume_depth(planes.nodes, volume_first_node));
  }

  // Whether the intersection child of `index` must be searched: it exists, p lies in its wedge
  // (Gerhards et al. 2015) and, with the depth test, is not closer than all of it.
  __device__ bool visits_intersection(std::uint32_t index, const QueryPoint& p) const {
    const PsvDeviceNode& n = planes.nodes[index];
    if (n.intersection == psv_no_node) return false;
    if (!is_capping_node(index)) {
      const double outside =
          rounded_sub(fabs(geometry::plane_value(n.plane, p.position)),
                      geometry::plane_error_bound(planes.filter, n.plane, false, p.position));
      const double wedge =
          planes.directional ? double(n.wedge) : rounded_mul(double(n.wedge), p.light_depth);
      if (outside > wedge) return false;
    }
    return !skipped_by_depth(n.intersection, p);
  }
};

// The stack of the stack and hybrid queries: at most `capacity` nodes in the thread's array.
class NodeStack {
 public:
  __device__ NodeStack(std::uint32_t* storage, std::uint32_t capacity)
      : storage_(storage), capacity_(capacity) {}
  __device__ bool empty() const { return size_ == 0; }
  __device__ bool full() const { return size_ == capacity_; }
  __device__ std::uint32_t size() const { return size_; }
  __device__ void push(std::uint32_t node) { storage_[size_++] = node; }  // requires !full()
  __device__ std::uint32_t pop() { return storage_[--size_]; }            // requires !empty()

 private:
  std::uint32_t* storage_;
  std::uint32_t capacity_;
  std::uint32_t size_ = 0;
};

}  // namespace psv
}  // namespace shadowcts::SHADOWCTS_KERNEL_NAMESPACE
