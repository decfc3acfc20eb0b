#pragma once
// Normal cones of the clusters (Deves et al. 2018, section 4, Fig. 4): the axis is the average of
// the triangles' unit normals, the half angle the largest angle between the axis and a normal.
// They cull clusters that face away from the light before the tree is built (section 5.3).
//
// Why the culling is exact only for closed meshes: a segment from a sample to a light outside a
// closed solid that passes through the solid leaves it last through a face whose outward normal
// points towards the light, so dropping the faces that point away keeps a blocker. Normals are
// therefore oriented outwards (by the sign of the mesh's volume), clusters of open meshes are
// never culled, nor those of a closed mesh whose bounding box may hold a point light.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts::metric {

struct NormalCone {
  glm::dvec3 axis{0.0, 0.0, 1.0};  // unit
  double half_angle = 0.0;         // radians, in [0, pi]
  bool cullable = false;           // closed, outward-oriented mesh
};

// Per mesh: +1 when its triangles wind counter-clockwise seen from outside (positive volume), -1
// when clockwise, 0 when the mesh is not closed or its volume is too small to tell the sign.
std::vector<int> closed_mesh_orientations(const Case& c);

// The normal cone of the triangles with the given case indices, all from one mesh; outward
// normals when the mesh's orientation is known. Zero-area triangles are never in a cluster.
NormalCone normal_cone(const Case& c, std::span<const std::uint32_t> triangles,
                       const std::vector<int>& orientations);

// Whether every point of every triangle within `reach` of `centre` (the cluster's bounding sphere)
// sees the light strictly behind its outward normal. point_light false: `light` is the unit
// direction towards a directional light. Conservative with a margin of 1e-9 radians.
bool faces_away_from_light(const NormalCone& cone, const glm::dvec3& centre, double reach,
                           bool point_light, const glm::dvec3& light);

}  // namespace shadowcts::metric
