#include "reference/metric/traversal.h"

#include <algorithm>
#include <optional>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/caster_blocks_sample.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts::metric {
namespace {

// The receiver half-space rule of the sample (DESIGN.md): no plane, so every caster counts, for a
// sample without a receiver.
geometry::ReceiverHalfSpace sample_half_space(const Case& c, const LightFrame& frame,
                                              const ViewSample& sample) {
  if (sample.receiver == no_receiver) return {};
  const Triangle& r = c.triangles[sample.receiver];
  const glm::dvec3 light =
      frame.directional ? glm::dvec3(c.light->direction) : glm::dvec3(c.light->position);
  return geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2),
                                       frame.directional, light);
}

}  // namespace

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

bool triangle_blocks_sample(const TraversalScene& scene, const ViewSample& sample,
                            const RaySpace& ray_space, std::uint32_t t,
                            std::optional<geometry::ReceiverHalfSpace>& half_space) {
  const Case& c = *scene.c;
  const Triangle& triangle = c.triangles[t];
  // The decision is shared with the device port (gpu/metric), so that both answer alike.
  return geometry::decide_caster<true>(
             ray_space, glm::dvec3(sample.position), scene.light.directional,
             scene.light.directional ? scene.light.direction : scene.light.position, triangle.v0,
             triangle.v1, triangle.v2, [&]() -> const geometry::ReceiverHalfSpace& {
               if (!half_space) half_space = sample_half_space(c, scene.frame, sample);
               return *half_space;
             }) == geometry::CasterDecision::blocks;
}

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

  std::optional<geometry::ReceiverHalfSpace> half_space;
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
          if (triangle_blocks_sample(scene, sample, ray_space, t, half_space)) return true;
        }
        ++counters.clusters_tested_without_hit;
        return false;
      });
}

}  // namespace shadowcts::metric
