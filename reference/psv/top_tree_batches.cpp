#include "reference/psv/top_tree_batches.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "reference/psv/top_tree_depth.h"

namespace shadowcts::psv {
namespace {

// The child a descent ended in: no_node while it is still empty.
std::uint32_t slot_of(const TopTree& tree, const Descent& d) {
  if (d.parent == no_node) return tree.root;
  return d.into_intersection ? tree.nodes[d.parent].intersection : tree.nodes[d.parent].positive;
}

// The reference updates a volume's depth with the depth of every triangle inserted below it, in
// insertion order, lowering it only on a strict '<': the result is the first smallest value of
// [own depth, then the subtree's in insertion order], and NaN only when the own depth is NaN.
// Volumes are numbered in insertion order and every volume below v comes after it, so one sweep
// from the last volume to the first finds, per volume, the smallest non-NaN depth of its subtree
// and which volume holds it first.
void set_subtree_depths(TopTree& tree, const HugePageVector<float>& own) {
  // Per volume: the smallest depth of its subtree so far and the first volume holding it. One
  // entry per child read: the children lie anywhere after the volume.
  struct Smallest {
    float depth = INFINITY;
    std::uint32_t holder = no_node;
  };
  const std::size_t volumes = own.size();
  HugePageVector<Smallest> smallest(volumes);
  const auto children = [&](std::size_t v, auto&& f) {
    for (std::uint32_t k = 0; k < nodes_per_volume; ++k) {
      const TopNode& n = tree.nodes[v * nodes_per_volume + k];
      if (n.positive != no_node) f(volume_of(n.positive));
      if (n.intersection != no_node) f(volume_of(n.intersection));
    }
  };
  constexpr std::size_t ahead = 16;  // volumes whose children's entries are fetched ahead
  for (std::size_t v = volumes; v-- > 0;) {
    if (v >= ahead) children(v - ahead, [&](std::uint32_t w) { __builtin_prefetch(&smallest[w]); });
    Smallest& mine = smallest[v];
    if (!std::isnan(own[v])) mine = {own[v], std::uint32_t(v)};
    children(v, [&](std::uint32_t w) {
      const Smallest& theirs = smallest[w];
      if (theirs.holder == no_node) return;
      if (mine.holder == no_node || theirs.depth < mine.depth ||
          (!(mine.depth < theirs.depth) && theirs.holder < mine.holder))
        mine = theirs;
    });
    const float depth = std::isnan(own[v]) ? own[v] : mine.depth;
    set_volume_depth(tree, std::uint32_t(v * nodes_per_volume), depth);
  }
}

// Every edge node's wedge: the largest triangle_wedge over the volumes of its intersection subtree
// (the triangles that straddled it on their way down). Volume by volume in parallel: the
// intersection nodes above a volume are the chain of ancestor links from it (the innermost one,
// then the innermost above that one's volume, ...), so each volume widens the wedges of its chain
// with its own triangle read once. The reference folds with std::max from 0, which never takes a
// NaN; a maximum does not depend on the order the volumes arrive in.
//
// Each link is a load from a volume anywhere in the tree that names the next one, so a chain
// alone waits on memory at every step: each range of volumes walks several chains at once, a step
// of each per round, every next node and triangle fetched a round before it is read.
void set_wedges(TopTree& tree, const PlaneSide& planes, const HugePageVector<float>& own) {
  const auto fetch_node = [&](std::uint32_t node) {
    __builtin_prefetch(&tree.nodes[node]);                  // its plane and wedge
    __builtin_prefetch(&tree.nodes[first_node(node) + 1]);  // its volume's ancestor link
  };
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, own.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& range) {
        struct Chain {
          std::uint32_t node;  // the next intersection node to widen
          float depth;         // the volume's own
          const Triangle* triangle;
        };
        constexpr std::size_t chains_in_flight = 16;
        Chain chains[chains_in_flight];
        std::size_t next = range.begin();
        // The next volume of the range below an intersection node, into `chain`.
        const auto start = [&](Chain& chain) {
          for (; next != range.end(); ++next) {
            const std::uint32_t first = std::uint32_t(next * nodes_per_volume);
            const std::uint32_t node = ancestor_link(tree, first);
            if (node == no_node) continue;
            chain = {node, own[next], &planes.triangles()[volume_triangle(tree, first)]};
            fetch_node(node);
            __builtin_prefetch(chain.triangle);
            __builtin_prefetch(reinterpret_cast<const char*>(chain.triangle + 1) - 1);
            ++next;
            return true;
          }
          return false;
        };
        std::size_t walking = 0;
        while (walking < chains_in_flight && start(chains[walking])) ++walking;
        while (walking > 0) {
          for (std::size_t i = 0; i < walking;) {
            Chain& chain = chains[i];
            const std::uint32_t node = chain.node;
            if (!is_capping_node(node)) {
              const float wedge =
                  triangle_wedge(planes, tree.nodes[node], *chain.triangle, chain.depth);
              std::atomic_ref<float> widest(tree.nodes[node].wedge);
              float current = widest.load(std::memory_order_relaxed);
              while (wedge > current &&
                     !widest.compare_exchange_weak(current, wedge, std::memory_order_relaxed)) {
              }
            }
            chain.node = ancestor_link(tree, node);
            if (chain.node != no_node) {
              fetch_node(chain.node);
              ++i;
            } else if (!start(chain)) {
              chain = chains[--walking];  // the last chain takes its place
            } else {
              ++i;
            }
          }
        }
      });
}

}  // namespace

void make_batch_volume(const PlaneSide& planes, std::uint32_t triangle, BatchVolume& volume) {
  volume.depth = triangle_light_depth(planes.light(), planes.triangles()[triangle]);
  planes.make_volume_planes(triangle, volume.nodes, volume.source);
}

void make_batch_volumes(const PlaneSide& planes, const std::vector<std::uint32_t>& triangles,
                        const std::vector<Descent>& descents, BatchVolumes& volumes) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t j = range.begin(); j != range.end(); ++j)
                        if (!descents[j].dropped)
                          make_batch_volume(planes, triangles[j], volumes[j]);
                    });
}

TopTree build_top_tree_in_batches(const PlaneSide& planes, const std::vector<std::uint32_t>& order,
                                  BuildStatistics& statistics, DescentEngine& engine,
                                  BatchWork& work) {
  TopTree tree;
  tree.nodes.reserve(order.size() * nodes_per_volume);
  tree.sources.reserve(order.size());
  HugePageVector<float> own_depth;
  own_depth.reserve(order.size());
  HugePageVector<std::uint32_t> first_level;  // per volume: nodes from the root to its first node
  first_level.reserve(order.size());
  statistics.height = 0;

  constexpr std::size_t largest_batch = std::size_t(1) << 15;
  std::vector<std::uint32_t> triangles;
  std::vector<Descent> descents;
  BatchVolumes volumes;
  for (std::size_t begin = 0; begin < order.size();) {
    const std::size_t size = std::min(
        {order.size() - begin, largest_batch, std::max<std::size_t>(1, own_depth.size() / 2)});
    triangles.assign(order.begin() + std::ptrdiff_t(begin),
                     order.begin() + std::ptrdiff_t(begin + size));
    descents.assign(size, Descent());
    volumes.resize(size);
    engine.descend_batch(tree, triangles, descents, volumes);
    // Commit in insertion order.
    for (std::size_t j = 0; j < size; ++j) {
      // The parents lie anywhere in the tree: fetch ahead.
      constexpr std::size_t ahead = 16;
      if (j + ahead < size && descents[j + ahead].parent != no_node) {
        const std::uint32_t parent = descents[j + ahead].parent;
        __builtin_prefetch(&tree.nodes[parent]);
        __builtin_prefetch(&first_level[volume_of(parent)]);
      }
      Descent& d = descents[j];
      if (!d.dropped) {
        const std::uint32_t filled = slot_of(tree, d);
        if (filled != no_node) {
          ++work.resumed_descents;
          engine.resume(tree, filled, triangles[j], d);
        }
      }
      if (d.dropped) {
        ++statistics.dropped_in_shadow;
        continue;
      }
      const BatchVolume& volume = volumes[j];
      const std::uint32_t first = std::uint32_t(tree.nodes.size());
      tree.nodes.insert(tree.nodes.end(), volume.nodes, volume.nodes + nodes_per_volume);
      tree.sources.push_back(volume.source);
      own_depth.push_back(volume.depth);
      // The height: the capping node of the volume with the deepest first node ends the longest
      // path (nodes never move once committed).
      const std::uint32_t level =
          d.parent == no_node ? 1
                              : first_level[volume_of(d.parent)] + d.parent % nodes_per_volume + 1;
      first_level.push_back(level);
      statistics.height = std::max<std::uint64_t>(statistics.height, level + capping_plane);
      set_volume_depth(tree, first, volume.depth);
      tree.nodes[first + 1].volume_word = d.ancestor;
      tree.nodes[first + 2].volume_word = triangles[j];
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
  // Side by side: the depth sweep is sequential, and the two write different fields (the first
  // node's volume word, the edge nodes' wedges) and read neither's.
  tbb::parallel_invoke([&] { set_subtree_depths(tree, own_depth); },
                       [&] { set_wedges(tree, planes, own_depth); });
  return tree;
}

}  // namespace shadowcts::psv
