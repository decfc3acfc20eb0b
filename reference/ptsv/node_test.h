#pragma once
// A node (or tile) against a shadow volume, and a sample against it (Sintorn 2014, Algorithm 1
// lines 11-19; Sintorn 2011, Algorithm 2). For each plane the trivial-reject point of the node's
// bounds is the one with the smallest plane value, the trivial-accept point the one with the
// largest: a node is rejected when its trivial-reject point is outside any plane, accepted when
// its trivial-accept point is inside all four, otherwise tested against the culling planes and
// refined.
//
// Consistency with the sample test, which decides the answer: a node is rejected or accepted only
// with a margin above the rounding of these evaluations, so every sample in a rejected node fails
// the sample test and every sample in an accepted node passes it and the receiver half-space rule
// (its own receiver aside, which the accept bias keeps out; the rule by the reject reach). All
// variants therefore give the same mask as testing every sample against every volume.
#include <array>
#include <cmath>

#include <glm/vec3.hpp>

#include "reference/ptsv/counters.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/triangle_setup.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

enum class NodeVerdict { reject, accept, refine };

struct NodeTolerances {
  double rounding = 0.0;  // above any rounding of a plane value at a node corner or a sample
  double accept_bias = 0.0;
  // node_bound: >= every |coordinate| of a node corner, sample or anchor ever evaluated;
  // scene_bound: >= every |coordinate| of a sample or triangle (the bias' scale).
  static NodeTolerances for_bounds(double node_bound, double scene_bound);
};

// The scene_bound every ptsv backend uses: Case::scale (casters, camera, light) and the
// |coordinates| of every regular sample.
double scene_bound(const Case& c, const ViewSamples& samples);

// Smallest and largest value of the plane over the bounds.
struct PlaneRange {
  double low, high;
};
PlaneRange plane_range(const Plane& plane, const std::array<glm::dvec3, 8>& corners);
PlaneRange plane_range(const Plane& plane, const WorldBox& box);

enum class CullingPlanes { none, extra, silhouette };

// reject_reach(): the largest reject reach of the node's samples (receiver_rule.h), asked only of
// a node the four planes accept. Every hit of the caster on a sample's segment lies on the
// triangle plane, so a node further behind it than that reach loses no sample to the receiver
// half-space rule and is accepted; a nearer one is refined down to the per-sample test.
template <class Bounds, class Reach>
NodeVerdict classify_node(const ShadowVolume& volume, const Bounds& bounds,
                          const NodeTolerances& tolerances, CullingPlanes culling,
                          TraversalCounters& counters, const Reach& reject_reach) {
  ++counters.node_tests;
  bool accept = true;
  double triangle_high = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Plane& plane = k < 3 ? volume.edges[std::size_t(k)] : volume.triangle_plane;
    const PlaneRange range = plane_range(plane, bounds);
    if (range.low > tolerances.rounding) {
      ++counters.trivial_rejects;
      return NodeVerdict::reject;
    }
    const double inside_by =
        k < 3 ? tolerances.rounding : tolerances.rounding + tolerances.accept_bias;
    if (!(range.high < -inside_by)) accept = false;
    if (k == 3) triangle_high = range.high;
  }
  if (accept && !(triangle_high < -(tolerances.rounding + reject_reach()))) accept = false;
  if (accept) {
    ++counters.trivial_accepts;
    return NodeVerdict::accept;
  }
  const int count = culling == CullingPlanes::extra        ? volume.extra_count
                    : culling == CullingPlanes::silhouette ? volume.silhouette_count
                                                           : 0;
  for (int k = 0; k < count; ++k) {
    const Plane& plane = culling == CullingPlanes::extra ? volume.extra[std::size_t(k)]
                                                         : volume.silhouette[std::size_t(k)];
    if (plane_range(plane, bounds).low > tolerances.rounding) {
      ++counters.culling_plane_rejects;
      return NodeVerdict::reject;
    }
  }
  return NodeVerdict::refine;
}

// Whether p lies on the outer side of plane k of the volume (edges 0-2, the triangle 3): the
// plane's double value where it is clear, the exact orientation sign within its rounding.
bool outside_plane_exactly(const ShadowVolume& volume, int k, const glm::vec3& p);

inline bool outside_plane(const ShadowVolume& volume, int k, const Plane& plane,
                          const glm::vec3& sample) {
  const glm::dvec3 p(sample);
  const double value = plane.at(p);
  // The unit normal is rounded by a few 2^-52 of |a||b| / |a x b| (its two vectors), and the
  // differences p - anchor by 2^-53 of themselves: 2^-44 of that covers both many times over.
  const glm::dvec3 offset = p - plane.anchor;
  const double bound = 0x1p-44 * (1.0 + volume.exact.condition[std::size_t(k)]) *
                       (std::fabs(offset.x) + std::fabs(offset.y) + std::fabs(offset.z));
  if (value > bound) return true;
  if (value < -bound) return false;
  return outside_plane_exactly(volume, k, sample);
}

// The per-sample volume test: inside the closed volume, and not the sample's own receiver. The
// caster then shadows the sample where the receiver half-space rule counts it
// (ReceiverRule::caster_counts).
inline bool sample_in_volume(const ShadowVolume& volume, const ViewSample& sample) {
  if (sample.receiver == volume.triangle) return false;
  for (int k = 0; k < 3; ++k)
    if (outside_plane(volume, k, volume.edges[std::size_t(k)], sample.position)) return false;
  return !outside_plane(volume, 3, volume.triangle_plane, sample.position);
}

}  // namespace shadowcts::ptsv
