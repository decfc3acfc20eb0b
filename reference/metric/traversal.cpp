#include "reference/metric/traversal.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts::metric {
namespace {

// Section 5.4, step 2: the slabs along the normal-cone axis reject a shadow segment that stays on
// one side of them. Both ends of the segment are exact in double up to the rounding of the dot
// products (a few 2^-53 * scale), which the margin covers many times over.
bool segment_meets_slabs(const TraversalScene& scene, const ClusterVolume& volume,
                         const glm::dvec3& from, const glm::dvec3& to) {
  const double lo = volume.slab_min - scene.frame.margin;
  const double hi = volume.slab_max + scene.frame.margin;
  const double s_from = glm::dot(volume.slab_normal, from);
  const double s_to = glm::dot(volume.slab_normal, to);
  return std::max(s_from, s_to) >= lo && std::min(s_from, s_to) <= hi;
}

}  // namespace

bool sample_is_shadowed(const TraversalScene& scene, const ViewSample& sample,
                        TraversalCounters& counters, std::vector<std::uint32_t>& stack) {
  const MetricTree& tree = *scene.tree;
  const LightFrame& frame = scene.frame;
  const glm::dvec3 p(sample.position);
  const LightSpaceQuery query = make_light_space_query(frame, p);
  if (query.at_light) return false;  // the segment is a point: the triangle test hits nothing
  const Case& c = *scene.c;
  const ShadowRay ray = frame.directional
                            ? ray_to_directional_light(sample.position, c.light->direction)
                            : segment_to_point_light(sample.position, c.light->position);
  const RaySpace ray_space = make_ray_space(ray);
  const glm::dvec3 segment_end =
      frame.directional ? p + scene.ray_length * frame.towards_light : frame.light_position;

  return for_each_candidate_element(
      tree, *scene.elements, frame, query, counters, stack, [&](std::uint32_t e) {
        const std::uint32_t cluster = (*scene.elements)[e].cluster;
        // Section 5.4, step 2: the slabs may still reject the segment without the triangles.
        if (!segment_meets_slabs(scene, (*scene.volumes)[cluster], p, segment_end)) return false;
        const Clustering& clustering = *scene.clustering;
        for (std::uint32_t k = clustering.cluster_begin[cluster];
             k < clustering.cluster_begin[cluster + 1]; ++k) {
          const std::uint32_t t = clustering.triangles[k];
          if (t == sample.receiver) continue;  // the receiver never shadows its own sample
          ++counters.triangle_tests;
          const Triangle& triangle = c.triangles[t];
          if (ray_hits_triangle(ray_space, triangle.v0, triangle.v1, triangle.v2)) return true;
          // The float test rounds each vertex on its own: beside an edge its miss may be a crack
          // (a vertex on another triangle's edge, found by fuzz_watertight). A hit there is
          // never wrong on a robust sample (the ray then passes within rounding of an open edge,
          // which makes the sample ambiguous, or of a covered one).
          if (ray_near_triangle_edge(ray_space, triangle.v0, triangle.v1, triangle.v2) &&
              scene.exact->blocks(triangle, MovedPoint{p, 0.0, {0, 0, 0}}))
            return true;
        }
        ++counters.clusters_tested_without_hit;
        return false;
      });
}

}  // namespace shadowcts::metric
