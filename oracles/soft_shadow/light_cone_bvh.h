#pragma once
// The caster triangles of a case (caster mesh, non-zero area) in a bounding volume hierarchy
// queried with a light cone: visit() reports every triangle that may come within `inflation` of the
// cone with apex p, axis d and a half-angle below pi/2 — the directions from p through the sun
// disk. Conservative: node tests use the box's bounding sphere and a relative slack far above the
// rounding error, so a triangle that meets the inflated cone is never skipped.
//
// Median splits along the longest centroid axis: the tree and the visiting order depend only on the
// case, never on the thread count.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

struct LightCone {
  glm::dvec3 apex{0.0};
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double half_angle = 0.0;         // radians, in (0, pi/2)
};

// A lower bound on the distance from point x to the cone (0 inside it), exact up to rounding.
double distance_to_cone(const LightCone& cone, const glm::dvec3& x);

class LightConeBvh {
 public:
  explicit LightConeBvh(const Case& c);

  std::size_t size() const { return triangles_.size(); }

  // Calls visit(triangle index) for every caster that may come within `inflation` of the cone.
  template <class Visitor>
  void visit(const LightCone& cone, double inflation, Visitor&& visit) const;

 private:
  struct Node {
    glm::dvec3 centre{0.0};            // of the node's box
    double radius = 0.0;               // half the box's diagonal
    std::uint32_t first_or_right = 0;  // leaf: first slot; inner: right child (left = index + 1)
    std::uint32_t count = 0;           // triangles in a leaf; 0 for an inner node
  };
  struct BuildItem;
  void build(std::vector<BuildItem>& items, std::size_t begin, std::size_t end, std::size_t node);
  static bool may_meet(const LightCone& cone, const glm::dvec3& centre, double radius,
                       double inflation);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> triangles_;
  std::vector<Node> triangle_spheres_;  // per slot: the triangle's own box sphere
};

template <class Visitor>
void LightConeBvh::visit(const LightCone& cone, double inflation, Visitor&& visit) const {
  if (nodes_.empty()) return;
  std::uint32_t stack[128];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0) {
    const std::uint32_t index = stack[--depth];
    const Node& node = nodes_[index];
    if (!may_meet(cone, node.centre, node.radius, inflation)) continue;
    if (node.count == 0) {
      stack[depth++] = node.first_or_right;
      stack[depth++] = index + 1;
      continue;
    }
    for (std::uint32_t slot = node.first_or_right; slot < node.first_or_right + node.count;
         ++slot) {
      const Node& sphere = triangle_spheres_[slot];
      if (may_meet(cone, sphere.centre, sphere.radius, inflation)) visit(triangles_[slot]);
    }
  }
}

}  // namespace shadowcts
