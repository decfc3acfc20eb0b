#pragma once
// The shadow-volume planes of a triangle and the side of a point against them.
//
// Planes are built in double from the float vertices and stored in the nodes as floats (the
// paper's layout). Edge planes take their two vertices in one canonical total order
// (lexicographic on x, y, z) and are then negated as a whole where needed, so the edge shared by
// two triangles gives the same plane bits with opposite signs in both. Every side decision is
// exact: the float plane answers when its value clears a proven error bound, and an exact
// orientation predicate on the triangle's vertices answers otherwise. That makes the tree the
// exact TOP tree of the float inputs, with closed volumes (a point on a plane is inside).
#include <atomic>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/psv/top_tree.h"
#include "shadowcts/case.h"
#include "shadowcts/geometry/plane_filter.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::psv {

class PlaneSide {
 public:
  // scene_bound: >= every |coordinate| of the triangles, the light position and the query points.
  PlaneSide(const HardShadowLight& light, const std::vector<Triangle>& triangles,
            double scene_bound);

  // Orientation of the triangle's capping plane towards the light: 1 when the light is on the
  // side its winding normal points to, -1 on the other side, 0 when the light lies in its plane
  // (or, for a directional light, the plane is parallel to it): the volume is flat.
  int light_side(const Triangle& t) const;

  // Writes the four planes of triangle `triangle` into nodes [first, first + 4) and its exact
  // recomputation recipe into `source`. Requires light_side(t) != 0 and non-zero area.
  void make_volume_planes(std::uint32_t triangle, TopNode* first, VolumeSource& source) const;

  // Exact sign of the plane of `node` at p: 1 outside (positive side), 0 on it, -1 inside.
  int side(const TopTree& tree, std::uint32_t node, const glm::dvec3& p) const;

  // The float plane's value at p and a bound on its distance from the exact plane's value.
  double value(const TopNode& node, const glm::dvec3& p) const;
  double error_bound(const TopNode& node, bool capping, const glm::dvec3& p) const;

  const HardShadowLight& light() const { return light_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  // The float filter's constants (shared with the GPU port, shadowcts/geometry/plane_filter.h).
  const geometry::PlaneFilter& filter() const { return filter_; }
  // Number of side() calls the float filter could not decide, and those a port decided with
  // exact_side from its own copy of the vertices (count_exact_fallbacks).
  std::uint64_t exact_fallbacks() const { return exact_fallbacks_.load(); }
  void count_exact_fallbacks(std::uint64_t n) const { exact_fallbacks_.fetch_add(n); }

  // Exact sign of plane k (0 to 3) of the volume with recipe `source` and triangle vertices
  // `vertices` at p.
  int exact_side(const VolumeSource& source, std::uint32_t k, const glm::dvec3 (&vertices)[3],
                 const glm::dvec3& p) const;

 private:
  int exact_side(const TopTree& tree, std::uint32_t node, const glm::dvec3& p) const;

  HardShadowLight light_;
  const std::vector<Triangle>& triangles_;
  geometry::PlaneFilter filter_;
  mutable std::atomic<std::uint64_t> exact_fallbacks_{0};
};

}  // namespace shadowcts::psv
