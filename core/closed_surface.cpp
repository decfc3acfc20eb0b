#include "shadowcts/closed_surface.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace shadowcts {
namespace {

// Exact position key; -0 and +0 are the same point.
using PositionKey = std::array<std::uint32_t, 3>;

PositionKey position_key(const glm::vec3& p) {
  PositionKey key{};
  for (int axis = 0; axis < 3; ++axis) {
    const float coordinate = p[axis] == 0.0f ? 0.0f : p[axis];
    key[static_cast<std::size_t>(axis)] = std::bit_cast<std::uint32_t>(coordinate);
  }
  return key;
}

struct DirectedEdge {
  PositionKey from, to;
  auto operator<=>(const DirectedEdge&) const = default;
};

// Adds the three directed edges of t unless two of its corners coincide.
void add_edges(const Triangle& t, std::vector<DirectedEdge>& edges) {
  const PositionKey a = position_key(t.v0), b = position_key(t.v1), c = position_key(t.v2);
  if (a == b || b == c || a == c) return;
  edges.push_back({a, b});
  edges.push_back({b, c});
  edges.push_back({c, a});
}

bool every_edge_once_each_way(std::vector<DirectedEdge>& edges) {
  if (edges.empty()) return false;
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  return std::all_of(edges.begin(), edges.end(), [&](const DirectedEdge& e) {
    return std::binary_search(edges.begin(), edges.end(), DirectedEdge{e.to, e.from});
  });
}

}  // namespace

bool is_closed_surface(std::span<const Triangle> triangles) {
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles) add_edges(t, edges);
  return every_edge_once_each_way(edges);
}

bool is_closed_surface(std::span<const Triangle> triangles, std::span<const std::uint32_t> subset) {
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * subset.size());
  for (const std::uint32_t i : subset) add_edges(triangles[i], edges);
  return every_edge_once_each_way(edges);
}

}  // namespace shadowcts
