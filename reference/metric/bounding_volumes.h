#pragma once
// Bounding volumes of the clusters (Deves et al. 2018, section 4): the covariance OBB of the
// cluster's vertices (Gottschalk et al. 1996) decides the shape: a capsule when its largest
// extent is at least twice every other one, else the smallest enclosing sphere (Gaertner 1999,
// CGAL's Min_sphere_of_spheres_d). The capsule's axis passes through the centre of the smallest
// circle enclosing the vertices projected on the plane orthogonal to the main OBB axis, its radius
// is that circle's, and its segment spans the main OBB extent. Two slabs along the normal-cone
// axis narrow either shape.
//
// Conservative by construction: the radius and the slab planes are enlarged until every vertex is
// inside in double arithmetic, then by a margin above the rounding of those checks, so that every
// vertex is inside exactly (the tests verify it with rational arithmetic).
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts::metric {

enum class VolumeShape : std::uint8_t { sphere, capsule };

struct ClusterVolume {
  VolumeShape shape = VolumeShape::sphere;
  // Sphere: the centre (axis_begin == axis_end). Capsule: the segment swept by the sphere.
  glm::dvec3 axis_begin{0.0}, axis_end{0.0};
  double radius = 0.0;  // every vertex is within it of the centre point or segment
  // Slabs: slab_min <= slab_normal . v <= slab_max for every vertex v.
  glm::dvec3 slab_normal{0.0, 0.0, 1.0};
  double slab_min = 0.0, slab_max = 0.0;
};

// The bounding volume of the triangles with the given case indices (at least one). Capsules only
// when allow_capsules (the `spheres` variant uses spheres alone). slab_axis: unit normal-cone axis.
ClusterVolume bound_cluster(const Case& c, std::span<const std::uint32_t> triangles,
                            bool allow_capsules, const glm::dvec3& slab_axis);

}  // namespace shadowcts::metric
