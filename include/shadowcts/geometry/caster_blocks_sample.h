#pragma once
// Whether one caster triangle shadows one view sample, as the hard-shadow algorithms that test
// triangles one by one decide it (the reference `metric`'s triangle_blocks_sample and its ports,
// host and device): the float watertight test (segment_triangle.h), decided again exactly beside
// an edge, where its miss may be a crack at a T-junction, and the receiver half-space rule
// (receiver_half_space.h), decided exactly. Every step is either the float test, whose bits are
// the same on host and device (rounded_arithmetic.h), or an exact predicate, so the answer is the
// same wherever it runs.
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/edge_proximity.h"
#include "shadowcts/geometry/exact_segment_triangle.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_triangle.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

enum class CasterDecision : std::uint8_t {
  passes,  // does not shadow the sample
  blocks,  // shadows it
  // Only with exact_segment_test = false: a float miss within rounding of an edge, or a float
  // answer at the light's end of the segment, for a triangle the rule lets count, which the exact
  // segment test must decide (a device defers it to the host: the
  // exact tests' expansions cost a kernel minutes of ptxas time and kilobytes of stack).
  needs_exact_segment_test,
};

// Whether the line of the ray certainly misses the triangle for the exact vertices and direction:
// the float edge functions (exact for the rounded ray-space vertices) have mixed signs, and none
// that decides it lies within the rounding of the ray-space transform (edge_proximity.h). The
// exact segment test then misses too, whatever the crossing's t.
SHADOWCTS_HD inline bool line_certainly_misses_triangle(const RaySpace& space, const glm::vec3& v0,
                                                        const glm::vec3& v1, const glm::vec3& v2) {
  if (space.zero_direction || ray_within_rounding_of_triangle_edge(space, v0, v1, v2)) return false;
  const RaySpaceVertex a = to_ray_space(space, v0);
  const RaySpaceVertex b = to_ray_space(space, v1);
  const RaySpaceVertex c = to_ray_space(space, v2);
  const double e[3] = {exact_edge_function(b, c), exact_edge_function(c, a),
                       exact_edge_function(a, b)};
  return (e[0] < 0.0 || e[1] < 0.0 || e[2] < 0.0) && (e[0] > 0.0 || e[1] > 0.0 || e[2] > 0.0);
}

// ray_space: the sample's float shadow ray (segment_to_point_light / ray_to_directional_light);
// p: the sample's position; light: the point light L, or the direction d towards a directional
// light (as HardShadowLight holds them). half_space_of() returns the sample's receiver
// half-space: it is called only once a triangle may block, so a caller can build it on first need
// (most samples never need its exact orientations).
template <bool exact_segment_test, class HalfSpaceOf>
SHADOWCTS_HD inline CasterDecision decide_caster(const RaySpace& ray_space, const glm::dvec3& p,
                                                 bool directional, const glm::dvec3& light,
                                                 const glm::vec3& v0, const glm::vec3& v1,
                                                 const glm::vec3& v2, HalfSpaceOf&& half_space_of) {
  const bool float_hit = ray_hits_triangle(ray_space, v0, v1, v2);
  // The float test rounds each vertex on its own: beside an edge its miss may be a crack (a
  // vertex on another triangle's edge, found by fuzz_watertight). A hit there is never wrong on a
  // robust sample away from the light (the ray then passes within rounding of an open edge, which
  // makes the sample ambiguous, or of a covered one). At the light's end of the segment neither
  // answer is certain: a light 1e-30 above a floor, or on a caster's edge, is where robust samples
  // got false shadows.
  const bool at_light_end = triangle_reaches_light_end(ray_space, v0, v1, v2);
  if (!float_hit && !at_light_end && !ray_near_triangle_edge(ray_space, v0, v1, v2))
    return CasterDecision::passes;
  const bool certain_hit = float_hit && !at_light_end;
  // Without the exact test, a miss whose line is certainly outside needs none: it is the exact
  // test's answer.
  if constexpr (!exact_segment_test)
    if (!certain_hit && line_certainly_misses_triangle(ray_space, v0, v1, v2))
      return CasterDecision::passes;
  // The receiver half-space rule: a hit counts only strictly on the light's side of the
  // receiver's plane, so a coplanar neighbour or the next face of a convex mesh is passed over.
  const ReceiverHalfSpace& half_space = half_space_of();
  const glm::dvec3 a(v0), b(v1), c(v2);
  const CasterReach reach = caster_reach(half_space, a, b, c);
  if (reach == CasterReach::no_hit) return CasterDecision::passes;
  if (!certain_hit) {
    if constexpr (!exact_segment_test) {
      return CasterDecision::needs_exact_segment_test;
    } else {
      if (!(directional ? ray_meets_triangle(p, light, a, b, c)
                        : segment_meets_triangle(p, light, a, b, c)))
        return CasterDecision::passes;
    }
  }
  return reach == CasterReach::every_hit || hit_on_light_side(half_space, p, a, b, c)
             ? CasterDecision::blocks
             : CasterDecision::passes;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
