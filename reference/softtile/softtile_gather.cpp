#include "reference/softtile/softtile_gather.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "reference/closed_mesh_culling.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/sun_disk_frame.h"

namespace shadowcts::softtile {
namespace {

struct Sphere {
  glm::dvec3 centre{0.0};
  double radius = 0.0;
};

// The bounding sphere of a box of points, padded by a relative margin.
Sphere box_sphere(const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  return {centre, radius * (1.0 + 1e-9) + 1e-9 * glm::length(centre)};
}

}  // namespace

glm::vec3 LightSpace::to_light(const glm::vec3& world) const {
  const glm::dvec3 w(world);
  return glm::vec3(glm::dot(w, x_axis), glm::dot(w, y_axis), glm::dot(w, z_axis));
}

Gathered gather(const Case& c, const ViewSamples& samples) {
  const SunDiskFrame frame = sun_disk_frame(c);
  Gathered out;
  out.sun = {frame.direction, frame.angular_radius};
  int binary_exponent = 0;
  std::frexp(c.scale(), &binary_exponent);  // S = m 2^binary_exponent, m in [1/2, 1)
  const double unit = std::ldexp(1.0, -binary_exponent);
  out.light_space = {unit * frame.x_axis, unit * frame.y_axis, unit * frame.direction};

  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  bool any = false;
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    lo = glm::min(lo, glm::dvec3(s.position));
    hi = glm::max(hi, glm::dvec3(s.position));
    any = true;
  }
  if (!any) return out;
  TileBound frame_bound;
  const Sphere receivers = box_sphere(lo, hi);
  frame_bound.a = receivers.centre;
  frame_bound.radius_a = receivers.radius;

  const double sin_a = std::sin(frame.angular_radius);
  // Light-facing faces of a closed mesh hide nothing its other faces do not, but only seen from
  // outside the solid: a sample inside it, or on it where the disk dips below the receiver's
  // plane (a wide sun), sees out through exactly those faces.
  const std::vector<bool> cull_light_facing = meshes_safe_for_face_culling(c, samples);
  std::size_t i = 0;
  while (i < c.triangles.size()) {
    // One cluster: consecutive triangles of the same mesh.
    const std::uint32_t mesh = c.triangles[i].mesh;
    const std::size_t end = std::min(c.triangles.size(), i + cluster_size);
    std::size_t stop = i;
    glm::dvec3 cluster_lo(std::numeric_limits<double>::max()),
        cluster_hi(-std::numeric_limits<double>::max());
    double cluster_highest = -std::numeric_limits<double>::max();
    while (stop < end && c.triangles[stop].mesh == mesh) {
      for (const glm::vec3& v :
           {c.triangles[stop].v0, c.triangles[stop].v1, c.triangles[stop].v2}) {
        cluster_lo = glm::min(cluster_lo, glm::dvec3(v));
        cluster_hi = glm::max(cluster_hi, glm::dvec3(v));
        cluster_highest = std::max(cluster_highest, glm::dot(glm::dvec3(v), frame.direction));
      }
      ++stop;
    }
    ++out.clusters_in;
    const Sphere cluster_sphere = box_sphere(cluster_lo, cluster_hi);
    GatheredCluster cluster;
    cluster.cone = shadow_cone(out.sun, cluster_sphere.centre, cluster_sphere.radius,
                               cluster_highest + 1e-9 * std::fabs(cluster_highest));
    cluster.first = std::uint32_t(out.triangles.size());
    if (!may_shadow(out.sun, cluster.cone, frame_bound)) {
      ++out.clusters_culled;
      out.triangles_culled += stop - i;
      i = stop;
      continue;
    }
    const bool closed = cull_light_facing[mesh];
    for (std::size_t k = i; k < stop; ++k) {
      if (!casts_shadow(c, k)) {
        ++out.triangles_culled;
        continue;
      }
      const Triangle& t = c.triangles[k];
      const glm::dvec3 v0(t.v0), v1(t.v1), v2(t.v2);
      if (closed) {
        // Faces the light for every direction q of the disk: n . q > 0 for all q within a of d
        // <=> n^ . d > sin(a) (a margin keeps rounding on the safe side).
        const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
        const double length = glm::length(n);
        if (length > 0.0 && glm::dot(n, frame.direction) / length > sin_a + 1e-9) {
          ++out.light_facing_dropped;
          continue;
        }
      }
      const glm::dvec3 t_lo = glm::min(v0, glm::min(v1, v2)), t_hi = glm::max(v0, glm::max(v1, v2));
      const Sphere sphere = box_sphere(t_lo, t_hi);
      const double highest = std::max({glm::dot(v0, frame.direction), glm::dot(v1, frame.direction),
                                       glm::dot(v2, frame.direction)});
      GatheredTriangle g;
      g.triangle = std::uint32_t(k);
      g.cone =
          shadow_cone(out.sun, sphere.centre, sphere.radius, highest + 1e-9 * std::fabs(highest));
      if (!may_shadow(out.sun, g.cone, frame_bound)) {
        ++out.triangles_culled;
        continue;
      }
      g.light_space = {out.light_space.to_light(t.v0), out.light_space.to_light(t.v1),
                       out.light_space.to_light(t.v2)};
      out.triangles.push_back(g);
    }
    cluster.count = std::uint32_t(out.triangles.size()) - cluster.first;
    if (cluster.count > 0) out.clusters.push_back(cluster);
    i = stop;
  }
  return out;
}

}  // namespace shadowcts::softtile
