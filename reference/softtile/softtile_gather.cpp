#include "reference/softtile/softtile_gather.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
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

GatherFrame gather_frame(const Case& c, const ViewSamples& samples) {
  const SunDiskFrame disk = sun_disk_frame(c);
  GatherFrame frame;
  frame.sun = {disk.direction, disk.angular_radius};
  int binary_exponent = 0;
  std::frexp(c.scale(), &binary_exponent);  // S = m 2^binary_exponent, m in [1/2, 1)
  const double unit = std::ldexp(1.0, -binary_exponent);
  frame.light_space = {unit * disk.x_axis, unit * disk.y_axis, unit * disk.direction};
  frame.sin_radius = std::sin(disk.angular_radius);

  // The regular samples' box: minima and maxima, the same for any partitioning.
  struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
    bool any = false;
  };
  const Box box = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, samples.samples.size(), 16384), Box(),
      [&](const tbb::blocked_range<std::size_t>& range, Box b) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const ViewSample& s = samples.samples[i];
          if (s.sample_class != SampleClass::regular) continue;
          b.lo = glm::min(b.lo, glm::dvec3(s.position));
          b.hi = glm::max(b.hi, glm::dvec3(s.position));
          b.any = true;
        }
        return b;
      },
      [](Box a, const Box& b) {
        a.lo = glm::min(a.lo, b.lo);
        a.hi = glm::max(a.hi, b.hi);
        a.any = a.any || b.any;
        return a;
      });
  frame.any_sample = box.any;
  if (!box.any) return frame;
  const Sphere receivers = box_sphere(box.lo, box.hi);
  frame.bound.a = receivers.centre;
  frame.bound.radius_a = receivers.radius;
  // Light-facing faces of a closed mesh hide nothing its other faces do not, but only seen from
  // outside the solid: a sample inside it, or on it where the disk dips below the receiver's
  // plane (a wide sun), sees out through exactly those faces.
  frame.cull_light_facing = meshes_safe_for_face_culling(c, samples);
  return frame;
}

std::size_t cluster_end(const Case& c, std::size_t first) {
  const std::uint32_t mesh = c.triangles[first].mesh;
  const std::size_t end = std::min(c.triangles.size(), first + cluster_size);
  std::size_t stop = first;
  while (stop < end && c.triangles[stop].mesh == mesh) ++stop;
  return stop;
}

GatheredCluster gather_cluster(const Case& c, const GatherFrame& frame, std::size_t first,
                               std::size_t stop, GatheredTriangles& triangles,
                               GatherCounts& counts) {
  const glm::dvec3& direction = frame.sun.direction;
  glm::dvec3 cluster_lo(std::numeric_limits<double>::max()),
      cluster_hi(-std::numeric_limits<double>::max());
  double cluster_highest = -std::numeric_limits<double>::max();
  for (std::size_t k = first; k < stop; ++k)
    for (const glm::vec3& v : {c.triangles[k].v0, c.triangles[k].v1, c.triangles[k].v2}) {
      cluster_lo = glm::min(cluster_lo, glm::dvec3(v));
      cluster_hi = glm::max(cluster_hi, glm::dvec3(v));
      cluster_highest = std::max(cluster_highest, glm::dot(glm::dvec3(v), direction));
    }
  ++counts.clusters_in;
  const Sphere cluster_sphere = box_sphere(cluster_lo, cluster_hi);
  GatheredCluster cluster;
  cluster.cone = shadow_cone(frame.sun, cluster_sphere.centre, cluster_sphere.radius,
                             cluster_highest + 1e-9 * std::fabs(cluster_highest));
  cluster.first = std::uint32_t(triangles.size());
  if (!may_shadow(frame.sun, cluster.cone, frame.bound)) {
    ++counts.clusters_culled;
    counts.triangles_culled += stop - first;
    return cluster;
  }
  const bool closed = frame.cull_light_facing[c.triangles[first].mesh];
  for (std::size_t k = first; k < stop; ++k) {
    if (!casts_shadow(c, k)) {
      ++counts.triangles_culled;
      continue;
    }
    const Triangle& t = c.triangles[k];
    const glm::dvec3 v0(t.v0), v1(t.v1), v2(t.v2);
    if (closed) {
      // Faces the light for every direction q of the disk: n . q > 0 for all q within a of d
      // <=> n^ . d > sin(a) (a margin keeps rounding on the safe side).
      const glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
      const double length = glm::length(n);
      if (length > 0.0 && glm::dot(n, direction) / length > frame.sin_radius + 1e-9) {
        ++counts.light_facing_dropped;
        continue;
      }
    }
    const glm::dvec3 t_lo = glm::min(v0, glm::min(v1, v2)), t_hi = glm::max(v0, glm::max(v1, v2));
    const Sphere sphere = box_sphere(t_lo, t_hi);
    const double highest =
        std::max({glm::dot(v0, direction), glm::dot(v1, direction), glm::dot(v2, direction)});
    GatheredTriangle g;
    g.triangle = std::uint32_t(k);
    g.cone =
        shadow_cone(frame.sun, sphere.centre, sphere.radius, highest + 1e-9 * std::fabs(highest));
    if (!may_shadow(frame.sun, g.cone, frame.bound)) {
      ++counts.triangles_culled;
      continue;
    }
    g.light_space = {frame.light_space.to_light(t.v0), frame.light_space.to_light(t.v1),
                     frame.light_space.to_light(t.v2)};
    triangles.push_back(g);
  }
  cluster.count = std::uint32_t(triangles.size()) - cluster.first;
  return cluster;
}

Gathered gather(const Case& c, const ViewSamples& samples) {
  const GatherFrame frame = gather_frame(c, samples);
  Gathered out;
  out.sun = frame.sun;
  out.light_space = frame.light_space;
  if (!frame.any_sample) return out;
  for (std::size_t i = 0; i < c.triangles.size();) {
    const std::size_t stop = cluster_end(c, i);
    const GatheredCluster cluster = gather_cluster(c, frame, i, stop, out.triangles, out);
    if (cluster.count > 0) out.clusters.push_back(cluster);
    i = stop;
  }
  return out;
}

}  // namespace shadowcts::softtile
