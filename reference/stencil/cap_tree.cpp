#include "reference/stencil/cap_tree.h"

#include <algorithm>

#include <glm/common.hpp>

namespace shadowcts::stencil {

CapTree::CapTree(const std::vector<LightCap>& caps) : boxes_(caps.size()), order_(caps.size()) {
  if (caps.empty()) return;
  std::vector<glm::dvec3> centres(caps.size());
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const LightCap& cap = caps[k];
    boxes_[k].lo = glm::min(cap.v[0], glm::min(cap.v[1], cap.v[2]));
    boxes_[k].hi = glm::max(cap.v[0], glm::max(cap.v[1], cap.v[2]));
    centres[k] = 0.5 * (boxes_[k].lo + boxes_[k].hi);
    order_[k] = std::uint32_t(k);
  }
  // Median splits along the widest axis of the centres: depth about log2(n / leaf), far below the
  // query's stack of 64.
  constexpr std::uint32_t leaf = 4;
  struct Task {
    std::uint32_t node, first, count;
  };
  nodes_.reserve(2 * caps.size() / leaf + 2);
  nodes_.push_back({});
  std::vector<Task> tasks{{0, 0, std::uint32_t(caps.size())}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    glm::dvec3 lo = boxes_[order_[task.first]].lo, hi = boxes_[order_[task.first]].hi;
    glm::dvec3 centre_lo = centres[order_[task.first]], centre_hi = centre_lo;
    for (std::uint32_t k = task.first; k < task.first + task.count; ++k) {
      lo = glm::min(lo, boxes_[order_[k]].lo), hi = glm::max(hi, boxes_[order_[k]].hi);
      centre_lo = glm::min(centre_lo, centres[order_[k]]);
      centre_hi = glm::max(centre_hi, centres[order_[k]]);
    }
    nodes_[task.node].lo = lo, nodes_[task.node].hi = hi;
    if (task.count <= leaf) {
      nodes_[task.node].first = task.first, nodes_[task.node].count = task.count;
      continue;
    }
    const glm::dvec3 extent = centre_hi - centre_lo;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t half = task.count / 2;
    const auto begin = order_.begin() + task.first;
    std::nth_element(begin, begin + half, begin + task.count,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centres[a][axis] < centres[b][axis] ||
                              (centres[a][axis] == centres[b][axis] && a < b);
                     });
    const auto children = std::uint32_t(nodes_.size());
    nodes_[task.node].first = children, nodes_[task.node].count = 0;
    nodes_.push_back({});
    nodes_.push_back({});
    tasks.push_back({children, task.first, half});
    tasks.push_back({children + 1, task.first + half, task.count - half});
  }
}

}  // namespace shadowcts::stencil
