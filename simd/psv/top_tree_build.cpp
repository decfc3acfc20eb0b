#include "simd/psv/top_tree_build.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>
#include <utility>

#include <sys/mman.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/psv/top_tree_depth.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::simd::psv {
namespace {

using ref::no_node;
using ref::nodes_per_volume;

// Where a triangle's descent stopped: the node whose empty child it replaces (which child, and the
// innermost intersection node above it), or a shadow leaf.
struct Descent {
  std::uint32_t parent = no_node;
  std::uint32_t ancestor = no_node;
  bool into_intersection = false;
  bool dropped = false;
};

struct TriangleVertices {
  glm::dvec3 v[3];
};

TriangleVertices vertices_of(const Triangle& t) {
  return {{glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)}};
}

// One node of the reference's descent (ref::build_top_tree): the next node, or no_node once the
// descent has reached an empty child or a shadow leaf (d.dropped).
std::uint32_t descend_step(const ref::TopTree& tree, const std::vector<VolumeCorners>& corners,
                           const PlaneSide& planes, std::uint32_t node, const TriangleVertices& t,
                           Descent& d) {
  const int location = planes.triangle_location(tree, node, corners[ref::volume_of(node)], t.v);
  d.parent = node;
  if (location > 0) {
    d.into_intersection = false;
    return tree.nodes[node].positive;
  }
  if (location < 0) {
    if (ref::is_capping_node(node)) {
      d.dropped = true;
      return no_node;
    }
    return node + 1;
  }
  d.into_intersection = true;
  d.ancestor = node;
  return tree.nodes[node].intersection;
}

// The descent from `node` on, continuing `d`.
void descend(const ref::TopTree& tree, const std::vector<VolumeCorners>& corners,
             const PlaneSide& planes, std::uint32_t node, const TriangleVertices& t, Descent& d) {
  while (node != no_node) node = descend_step(tree, corners, planes, node, t, d);
}

void prefetch_node(const ref::TopTree& tree, const std::vector<VolumeCorners>& corners,
                   std::uint32_t node) {
  __builtin_prefetch(&tree.nodes[node]);
  __builtin_prefetch(&corners[ref::volume_of(node)]);
}

// Descents of several triangles interleaved node by node: a descent waits for memory at every
// node (the tree is far larger than the caches), so while one node is fetched (prefetched) the
// others are tested.
template <class Next, class Done>
void interleaved_descents(const ref::TopTree& tree, const std::vector<VolumeCorners>& corners,
                          const PlaneSide& planes, Next&& next, Done&& done) {
  constexpr int in_flight = 8;
  struct Walk {
    std::size_t item = 0;
    TriangleVertices t;
    std::uint32_t node = no_node;
    Descent d;
    bool active = false;
  };
  Walk walks[in_flight];
  const auto start = [&](Walk& w) {
    const Triangle* triangle = next(w.item);
    w.active = triangle != nullptr;
    if (!w.active) return;
    w.t = vertices_of(*triangle);
    w.d = Descent();
    w.node = tree.root;
  };
  int active = 0;
  for (Walk& w : walks) {
    start(w);
    active += w.active ? 1 : 0;
  }
  while (active > 0) {
    for (Walk& w : walks) {
      if (!w.active) continue;
      if (w.node != no_node) w.node = descend_step(tree, corners, planes, w.node, w.t, w.d);
      if (w.node != no_node) {
        prefetch_node(tree, corners, w.node);
        continue;
      }
      done(w.item, w.d);
      start(w);
      if (!w.active) --active;
    }
  }
}

// The child slot a descent ended in: no_node while it is still empty.
std::uint32_t slot_of(const ref::TopTree& tree, const Descent& d) {
  if (d.parent == no_node) return tree.root;
  return d.into_intersection ? tree.nodes[d.parent].intersection : tree.nodes[d.parent].positive;
}

// Asks for transparent huge pages behind a reserved (not yet touched) array: the descents and
// queries jump through hundreds of megabytes, and with 4 KiB pages nearly every node visit also
// misses the TLB. Only advice: where the kernel declines, nothing changes.
template <class T>
void advise_huge_pages(const std::vector<T>& v) {
  constexpr std::uintptr_t huge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin =
      (reinterpret_cast<std::uintptr_t>(v.data()) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end =
      (reinterpret_cast<std::uintptr_t>(v.data() + v.capacity())) & ~(huge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// What a triangle of a batch brings to its commit, computed in parallel.
struct Candidate {
  Descent descent;
  float depth = 0.0f;
  ref::TopNode nodes[nodes_per_volume];
  ref::VolumeSource source;
};

// The reference updates a volume's depth with the depth of every triangle inserted below it, in
// insertion order, lowering it only on a strict '<': the result is the first smallest value of
// [own depth, then the subtree's in insertion order], and NaN only when the own depth is NaN.
// Volumes are numbered in insertion order and every volume below v comes after it, so one sweep
// from the last volume to the first finds, per volume, the smallest non-NaN depth of its subtree
// and which volume holds it first.
void set_subtree_depths(ref::TopTree& tree, const std::vector<float>& own) {
  const std::size_t volumes = own.size();
  std::vector<float> best(volumes, INFINITY);
  std::vector<std::uint32_t> holder(volumes, no_node);
  const auto improves = [&](float value, std::uint32_t index, std::size_t v) {
    if (holder[v] == no_node || value < best[v]) return true;
    return !(best[v] < value) && index < holder[v];
  };
  for (std::size_t v = volumes; v-- > 0;) {
    if (!std::isnan(own[v])) {
      best[v] = own[v];
      holder[v] = std::uint32_t(v);
    }
    for (std::uint32_t k = 0; k < nodes_per_volume; ++k) {
      const ref::TopNode& n = tree.nodes[v * nodes_per_volume + k];
      for (const std::uint32_t child : {n.positive, n.intersection}) {
        if (child == no_node) continue;
        const std::uint32_t w = ref::volume_of(child);
        if (holder[w] != no_node && improves(best[w], holder[w], v)) {
          best[v] = best[w];
          holder[v] = holder[w];
        }
      }
    }
    const float depth = std::isnan(own[v]) ? own[v] : best[v];
    ref::set_volume_depth(tree, std::uint32_t(v * nodes_per_volume), depth);
  }
}

// Every edge node's wedge: the largest triangle_wedge over the volumes of its intersection subtree
// (the triangles that straddled it on their way down), folded as the reference folds it.
void set_wedges(ref::TopTree& tree, const ref::PlaneSide& planes, const std::vector<float>& own) {
  const std::size_t node_count = tree.nodes.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, node_count, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<std::uint32_t> pending;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        ref::TopNode& node = tree.nodes[i];
                        if (ref::is_capping_node(std::uint32_t(i)) || node.intersection == no_node)
                          continue;
                        float wedge = node.wedge;
                        pending.assign(1, node.intersection);
                        while (!pending.empty()) {
                          const std::uint32_t first = pending.back();
                          pending.pop_back();
                          const std::uint32_t v = ref::volume_of(first);
                          const Triangle& t = planes.triangles()[ref::volume_triangle(tree, first)];
                          wedge = std::max(wedge, ref::triangle_wedge(planes, node, t, own[v]));
                          for (std::uint32_t k = 0; k < nodes_per_volume; ++k) {
                            const ref::TopNode& n = tree.nodes[first + k];
                            if (n.positive != no_node) pending.push_back(n.positive);
                            if (n.intersection != no_node) pending.push_back(n.intersection);
                          }
                        }
                        node.wedge = wedge;
                      }
                    });
}

// Nodes on the longest root-to-leaf path, from the last volume to the first.
std::uint64_t longest_path(const ref::TopTree& tree) {
  if (tree.root == no_node) return 0;
  std::vector<std::uint32_t> height(tree.nodes.size(), 0);
  const auto of = [&](std::uint32_t node) { return node == no_node ? 0u : height[node]; };
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    const ref::TopNode& n = tree.nodes[i];
    std::uint32_t below = std::max(of(n.positive), of(n.intersection));
    if (!ref::is_capping_node(std::uint32_t(i))) below = std::max(below, height[i + 1]);
    height[i] = below + 1;
  }
  return height[tree.root];
}

}  // namespace

std::vector<std::uint32_t> insertion_order(const Case& c, const ref::PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           std::uint64_t seed, ref::BuildStatistics& statistics) {
  constexpr std::int8_t not_a_caster = 2;
  std::vector<std::int8_t> light_side(c.triangles.size(), not_a_caster);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        if (casts_shadow(c, i))
                          light_side[i] = std::int8_t(planes.light_side(c.triangles[i]));
                    });
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (light_side[i] == not_a_caster) continue;
    ++statistics.casters;
    if (light_side[i] == 0) {
      ++statistics.culled_flat;
      continue;
    }
    if (face_culling[c.triangles[i].mesh] && light_side[i] > 0) {
      ++statistics.culled_front_facing;
      continue;
    }
    order.push_back(std::uint32_t(i));
  }
  // The reference's shuffle, draw for draw.
  std::mt19937_64 random(seed);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random() % i]);
  return order;
}

ref::TopTree build_top_tree(const Case& c, const PlaneSide& planes,
                            const std::vector<std::uint32_t>& order,
                            ref::BuildStatistics& statistics, std::vector<VolumeCorners>& corners,
                            BuildWork& work) {
  const ref::PlaneSide& exact = planes.exact();
  ref::TopTree tree;
  tree.nodes.reserve(order.size() * nodes_per_volume);
  tree.sources.reserve(order.size());
  corners.clear();
  corners.reserve(order.size());
  advise_huge_pages(tree.nodes);
  advise_huge_pages(corners);
  std::vector<float> own_depth;
  own_depth.reserve(order.size());

  constexpr std::size_t largest_batch = std::size_t(1) << 15;
  std::vector<Candidate> batch;
  for (std::size_t begin = 0; begin < order.size();) {
    const std::size_t size = std::min(
        {order.size() - begin, largest_batch, std::max<std::size_t>(1, own_depth.size() / 2)});
    batch.resize(size);
    // Descend the tree as it stands, and prepare the volume, in parallel.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size, 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::size_t r = range.begin();
                        const auto next = [&](std::size_t& item) -> const Triangle* {
                          if (r == range.end()) return nullptr;
                          // The triangles lie in the scene's order, not the shuffled one:
                          // fetch ahead.
                          if (r + 8 < range.end())
                            __builtin_prefetch(&c.triangles[order[begin + r + 8]]);
                          item = r++;
                          return &c.triangles[order[begin + item]];
                        };
                        const auto done = [&](std::size_t item, const Descent& d) {
                          Candidate& candidate = batch[item];
                          candidate.descent = d;
                          if (d.dropped) return;
                          const std::uint32_t triangle = order[begin + item];
                          candidate.depth =
                              ref::triangle_light_depth(exact.light(), c.triangles[triangle]);
                          exact.make_volume_planes(triangle, candidate.nodes, candidate.source);
                        };
                        interleaved_descents(tree, corners, planes, next, done);
                      });
    // Commit in insertion order.
    for (std::size_t j = 0; j < size; ++j) {
      Candidate& candidate = batch[j];
      const std::uint32_t triangle = order[begin + j];
      Descent& d = candidate.descent;
      if (!d.dropped) {
        const std::uint32_t filled = slot_of(tree, d);
        if (filled != no_node) {
          ++work.resumed_descents;
          descend(tree, corners, planes, filled, vertices_of(c.triangles[triangle]), d);
        }
      }
      if (d.dropped) {
        ++statistics.dropped_in_shadow;
        continue;
      }
      const std::uint32_t first = std::uint32_t(tree.nodes.size());
      tree.nodes.insert(tree.nodes.end(), candidate.nodes, candidate.nodes + nodes_per_volume);
      tree.sources.push_back(candidate.source);
      own_depth.push_back(candidate.depth);
      const Triangle& t = c.triangles[triangle];
      corners.push_back({t.v0, t.v1, t.v2});
      ref::set_volume_depth(tree, first, candidate.depth);
      tree.nodes[first + 1].volume_word = d.ancestor;
      tree.nodes[first + 2].volume_word = triangle;
      if (d.parent == no_node)
        tree.root = first;
      else if (d.into_intersection)
        tree.nodes[d.parent].intersection = first;
      else
        tree.nodes[d.parent].positive = first;
      ++statistics.volumes;
    }
    begin += size;
    ++work.batches;
  }
  set_subtree_depths(tree, own_depth);
  set_wedges(tree, exact, own_depth);
  statistics.height = longest_path(tree);
  return tree;
}

}  // namespace shadowcts::simd::psv
