#pragma once
// Paper II's light hierarchy (Sections 3.3, 4.4): lights sorted by the Morton code of their
// centres, discretized in the box around all centres; 32 consecutive lights form a node of the
// first level, 32 consecutive nodes a node of the next, up to one root. Leaves are the lights'
// bounding spheres; nodes store the float box around their children (rounded outwards, so it
// holds every child exactly). Traversal is depth first per query box.
#include <cstdint>
#include <vector>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"

namespace shadowcts {

class LightBvh {
 public:
  static constexpr std::uint32_t branching = 32;

  explicit LightBvh(const std::vector<RangedLight>& lights);

  // Lights in Morton order: light_order()[leaf] is the light index of a leaf.
  const std::vector<std::uint32_t>& light_order() const { return order_; }
  // levels()[0] are the nodes over the leaves (32 leaves each), the last level is the root.
  const std::vector<std::vector<Aabb>>& levels() const { return levels_; }
  // The box around one light's sphere (float, rounded outwards).
  const Aabb& leaf_box(std::uint32_t leaf) const { return leaf_boxes_[leaf]; }

  // Depth-first traversal: every light whose node boxes all overlap `box` is handed to
  // accept(light_index), in Morton order; accept decides with its own exact test. Returns the
  // number of node boxes tested (Paper II's traversal work; leaves count when they are tested by
  // accept, not here).
  template <class Accept>
  std::uint64_t traverse(const Aabb& box, Accept&& accept) const;

 private:
  static bool overlap(const Aabb& a, const Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
           a.min.z <= b.max.z && b.min.z <= a.max.z;
  }

  std::vector<std::uint32_t> order_;
  std::vector<Aabb> leaf_boxes_;
  std::vector<std::vector<Aabb>> levels_;
};

template <class Accept>
std::uint64_t LightBvh::traverse(const Aabb& box, Accept&& accept) const {
  if (levels_.empty()) return 0;
  std::uint64_t tested = 1;
  const std::size_t top = levels_.size() - 1;
  if (!overlap(levels_[top][0], box)) return tested;
  // An explicit stack of (level, node); children are pushed in reverse so they pop in order.
  struct Entry {
    std::uint32_t level, node;
  };
  Entry stack[64 * branching];
  std::size_t size = 0;
  stack[size++] = {std::uint32_t(top), 0};
  while (size > 0) {
    const Entry e = stack[--size];
    const std::uint64_t first = std::uint64_t(e.node) * branching;
    if (e.level == 0) {
      const std::uint64_t last = std::min<std::uint64_t>(first + branching, order_.size());
      for (std::uint64_t leaf = first; leaf < last; ++leaf) {
        ++tested;
        if (overlap(leaf_boxes_[leaf], box)) accept(order_[leaf]);
      }
      continue;
    }
    const std::vector<Aabb>& children = levels_[e.level - 1];
    const std::uint64_t last = std::min<std::uint64_t>(first + branching, children.size());
    for (std::uint64_t child = last; child-- > first;) {
      ++tested;
      if (overlap(children[child], box)) stack[size++] = {e.level - 1, std::uint32_t(child)};
    }
  }
  return tested;
}

}  // namespace shadowcts
