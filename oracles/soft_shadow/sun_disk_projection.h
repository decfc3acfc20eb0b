#pragma once
// Central projection of a caster triangle from a sample onto the sun disk, in double precision:
// the one place where the soft-shadow oracles round. "Disk units" are the plane perpendicular to
// the light direction d at unit distance from the sample, scaled by 1 / tan(a), so the disk is the
// unit disk around the origin.
#include <array>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/sun_disk_frame.h"

namespace shadowcts {

// A convex polygon in disk units: the projection of a triangle, clipped where needed. A square
// (4 corners) clipped by three half-planes has at most 7 corners.
struct DiskPolygon {
  std::array<glm::dvec2, 7> corners{};
  int count = 0;  // 0: the projection has no area (behind the sample, or seen edge-on)
};

// How a triangle whose vertices all lie strictly in front of the sample is projected: by its three
// projected vertices (the exact oracle: shared vertices project to the same doubles, so shared
// edges match exactly), or, like every other triangle, homogeneously clipped to the square.
enum class FrontProjection { vertices, clipped };

// The projection of the triangle with vertices v from p, intersected with the square
// [-half_width, half_width]^2 where it is clipped. Triangles with vertices on both sides of the
// fragment plane (z = 0) are handled homogeneously: the projection of the part in front of p is
// { X : s (h_i x h_j) . (X, Y, 1) >= 0 for the three edges }, h the vertices in homogeneous disk
// coordinates and s the sign of det(h0, h1, h2), so no vertex is ever divided by its z.
DiskPolygon project_triangle(const SunDiskFrame& frame, const glm::dvec3& p,
                             const std::array<glm::dvec3, 3>& v, FrontProjection front,
                             double half_width);

// The smallest angle between d and a direction from p to a point of the closed triangle (v
// relative to p), in radians, rounded down by far more than its rounding error (a conservative
// lower bound); 0 when d points into the triangle's cone or p lies on the triangle.
double angle_to_triangle(const glm::dvec3& d, const std::array<glm::dvec3, 3>& w);

// A lower bound on the distance from p to the closed triangle: the nearest edge's distance where
// p's projection onto the plane lies certainly outside the triangle, else the smaller of that and
// the plane's distance; rounded down by far more than its rounding error, needles and slivers
// included.
double distance_to_triangle(const glm::dvec3& p, const std::array<glm::dvec3, 3>& v);

}  // namespace shadowcts
