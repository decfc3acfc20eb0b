#pragma once
// The gather pass: the whole scene culled once per frame, clusters first, then triangles. What
// survives is packed densely with its light-space vertices and truncated shadow cones.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/softtile/shadow_cone.h"
#include "shadowcts/case.h"
#include "shadowcts/huge_pages.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::softtile {

// Light space: z towards the sun, x and y any orthogonal pair perpendicular to it (the post's
// to_light_space_matrix), all three of length 2^k with 2^k S in [1/2, 1) for the case's scale S.
// The fragment setup's edge functions are homogeneous in light-space coordinates (degree 2, the
// determinant degree 3, and the rasterized crossings degree 0), so a power of two changes no
// decision and no mask, while it keeps their float32 products of three coordinates from
// overflowing (S from about 2^40) or losing precision to underflow (S below about 2^-40).
struct LightSpace {
  glm::dvec3 x_axis, y_axis, z_axis;
  glm::vec3 to_light(const glm::vec3& world) const;  // rounded to float, as the shader reads it
};

struct GatheredTriangle {
  std::uint32_t triangle;  // index into Case::triangles
  std::array<glm::vec3, 3> light_space;
  ShadowCone cone;
};

// 72 bytes a triangle, 72 MB at a million: in huge pages (a fresh 4 KiB page costs a fault,
// huge_pages.h).
using GatheredTriangles = HugePageVector<GatheredTriangle>;

struct GatheredCluster {
  ShadowCone cone;
  std::uint32_t first = 0, count = 0;  // range in Gathered::triangles
};

struct GatherCounts {
  std::uint64_t clusters_in = 0, clusters_culled = 0, triangles_culled = 0,
                light_facing_dropped = 0;
  GatherCounts& operator+=(const GatherCounts& o) {
    clusters_in += o.clusters_in;
    clusters_culled += o.clusters_culled;
    triangles_culled += o.triangles_culled;
    light_facing_dropped += o.light_facing_dropped;
    return *this;
  }
};

// With its counters (the base).
struct Gathered : GatherCounts {
  SunGeometry sun;
  LightSpace light_space;
  GatheredTriangles triangles;
  std::vector<GatheredCluster> clusters;
};

// What the gather of every cluster reads: the sun, light space, the bound of the frame's relevant
// samples and the meshes whose light-facing triangles it drops. No relevant sample: nothing else.
struct GatherFrame {
  SunGeometry sun;
  LightSpace light_space;
  double sin_radius = 0.0;
  bool any_sample = false;
  TileBound bound;                      // a sphere
  std::vector<bool> cull_light_facing;  // per mesh
};

// Mesh clusters: runs of up to this many consecutive triangles of one mesh (the case has no
// renderer clusters, so the reference makes the simplest ones).
inline constexpr std::uint32_t cluster_size = 64;

// Keeps every caster triangle whose truncated cone may reach the bounding sphere of the frame's
// relevant samples (the post culls against the view frustum, extended because geometry outside
// it shadows inside it; the samples' bound is that region, tight), and drops triangles that face
// the light for every direction of the disk only in meshes proven closed: a ray towards the light
// from outside a closed mesh that enters it also leaves it through a face that does not.
// gather_frame(), then gather_cluster() for each cluster in triangle order.
Gathered gather(const Case& c, const ViewSamples& samples);

GatherFrame gather_frame(const Case& c, const ViewSamples& samples);

// The end of the cluster that starts at triangle `first` (< the triangle count).
std::size_t cluster_end(const Case& c, std::size_t first);

// The cluster of triangles [first, stop): its survivors appended to `triangles` in order, its
// counts added to `counts`; the returned cluster's range is in `triangles` (count 0: none kept).
GatheredCluster gather_cluster(const Case& c, const GatherFrame& frame, std::size_t first,
                               std::size_t stop, GatheredTriangles& triangles,
                               GatherCounts& counts);

}  // namespace shadowcts::softtile
