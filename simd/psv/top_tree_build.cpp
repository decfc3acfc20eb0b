#include "simd/psv/top_tree_build.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/psv/top_tree_depth.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "simd/psv/descent_lanes.h"
#include "simd/psv/top_tree_depth.h"

namespace shadowcts::simd::psv {
namespace {

using ref::no_node;
using ref::nodes_per_volume;

using ref::Descent;

struct TriangleVertices {
  glm::dvec3 v[3];
};

TriangleVertices vertices_of(const Triangle& t) {
  return {{glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)}};
}

// One node of the reference's descent (ref::build_top_tree): the next node, or no_node once the
// descent has reached an empty child or a shadow leaf (d.dropped).
std::uint32_t descend_step(const ref::TopTree& tree, const VolumeCornerArray& corners,
                           const PlaneSide& planes, std::uint32_t node, const TriangleVertices& t,
                           Descent& d) {
  return ref::step_by_location(
      tree, node, planes.triangle_location(tree, node, corners[ref::volume_of(node)], t.v), d);
}

// The descent from `node` on, continuing `d`.
void descend(const ref::TopTree& tree, const VolumeCornerArray& corners, const PlaneSide& planes,
             std::uint32_t node, const TriangleVertices& t, Descent& d) {
  while (node != no_node) node = descend_step(tree, corners, planes, node, t, d);
}

// The descents of a batch on oneTBB threads with this port's plane tests. The corners of the
// tree's volumes are kept beside it, appended as the tree grows.
class ParallelDescents final : public ref::DescentEngine {
 public:
  ParallelDescents(const Case& c, const PlaneSide& planes, VolumeCornerArray& corners)
      : c_(c), planes_(planes), corners_(corners) {}

  void descend_batch(const ref::TopTree& tree, const std::vector<std::uint32_t>& triangles,
                     std::vector<Descent>& out, ref::BatchVolumes& volumes) override {
    add_corners(tree);  // the last batch's
    batch_triangles_ = triangles;
    batch_corners_.resize(triangles.size());
    next_item_ = 0;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        descend_in_lanes(tree, corners_, planes_, c_.triangles, triangles.data(),
                                         range.begin(), range.end(), out.data());
                        // The volumes and corners of those that stay, their triangles in cache:
                        // the reference's make_batch_volume, its depths in lanes.
                        triangle_light_depths(planes_.exact().light(), c_.triangles,
                                              triangles.data(), out.data(), range.begin(),
                                              range.end(), volumes.data());
                        for (std::size_t item = range.begin(); item != range.end(); ++item) {
                          if (out[item].dropped) continue;
                          planes_.exact().make_volume_planes(triangles[item], volumes[item].nodes,
                                                             volumes[item].source);
                          const Triangle& t = c_.triangles[triangles[item]];
                          batch_corners_[item] = {t.v0, t.v1, t.v2};
                        }
                      });
  }

  void resume(const ref::TopTree& tree, std::uint32_t node, std::uint32_t triangle,
              Descent& d) override {
    add_corners(tree);
    descend(tree, corners_, planes_, node, vertices_of(c_.triangles[triangle]), d);
  }

  // Appends the corners of the volumes committed since the last call: the batch's triangles that
  // stayed, in batch order (each triangle occurs once in a batch; the others were dropped).
  void add_corners(const ref::TopTree& tree) {
    for (std::size_t v = corners_.size(); v < tree.sources.size(); ++v) {
      const std::uint32_t triangle =
          ref::volume_triangle(tree, std::uint32_t(v * nodes_per_volume));
      while (batch_triangles_[next_item_] != triangle) ++next_item_;
      corners_.push_back(batch_corners_[next_item_++]);
    }
  }

 private:
  const Case& c_;
  const PlaneSide& planes_;
  VolumeCornerArray& corners_;
  // The batch being committed: its triangles, and the corners of those its descents kept.
  std::vector<std::uint32_t> batch_triangles_;
  VolumeCornerArray batch_corners_;
  std::size_t next_item_ = 0;
};

}  // namespace

std::vector<std::uint32_t> insertion_order(const Case& c, const std::vector<std::uint8_t>& casts,
                                           const ref::PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           const CasterReach& reach, std::uint64_t seed,
                                           ref::BuildStatistics& statistics) {
  // Per triangle: its light side (-1, 0, 1), or why it has none.
  constexpr std::int8_t not_a_caster = 2, out_of_reach = 3;
  std::vector<std::int8_t> light_side(c.triangles.size(), not_a_caster);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, c.triangles.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        if (!casts[i]) continue;
                        const Triangle& t = c.triangles[i];
                        light_side[i] = reach.may_reach(t.v0, t.v1, t.v2)
                                            ? std::int8_t(planes.light_side(t))
                                            : out_of_reach;
                      }
                    });
  std::vector<std::uint32_t> order;
  order.reserve(c.triangles.size());  // one allocation: each fresh page is a fault
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (light_side[i] == not_a_caster) continue;
    ++statistics.casters;
    if (light_side[i] == out_of_reach) {
      ++statistics.culled_out_of_reach;
      continue;
    }
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
                            ref::BuildStatistics& statistics, VolumeCornerArray& corners,
                            BuildWork& work) {
  corners.clear();
  corners.reserve(order.size());
  ParallelDescents engine(c, planes, corners);
  ref::TopTree tree =
      ref::build_top_tree_in_batches(planes.exact(), order, statistics, engine, work);
  engine.add_corners(tree);  // the last batch's
  return tree;
}

}  // namespace shadowcts::simd::psv
