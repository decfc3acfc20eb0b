#include "reference/metric/metric_tree.h"

#include <algorithm>
#include <utility>

namespace shadowcts::metric {

std::uint64_t tree_depth(const MetricTree& tree) {
  if (tree.nodes.empty()) return 0;
  std::uint64_t deepest = 0;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    for (std::uint32_t child : tree.nodes[node].child)
      if (child != no_node) stack.push_back({child, depth + 1});
  }
  return deepest;
}

}  // namespace shadowcts::metric
