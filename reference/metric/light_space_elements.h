#pragma once
// Cluster volumes seen from the light (Deves et al. 2018, sections 5.2 and 6).
//
// Point light O: a sphere (C, r) becomes a cone of directions around C - O with angular radius
// arcsin(r / |OC|); a capsule (segment AB, radius r) the paper's conservative capsule-cone: the
// great-circle arc of the directions of AB with the largest angular radius arcsin(r / |OX|), X the
// point of AB closest to O. Distances are angles on the sphere of directions.
// Directional light d: spheres and capsules are swept along d into cylinders and swept capsules;
// seen along d they are disks and 2D capsules in the plane orthogonal to d, with Euclidean
// distances there (section 6, "Discussion and limitations").
//
// Every element is a centre (a point or a segment / arc) and a radius: its region is the set of
// query points within the radius of the centre. A light inside a volume makes the element cover
// every direction. Radii include `margin` (see LightFrame) so that no blocker a float triangle test
// can report is ever culled.
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "reference/metric/angular_distance.h"
#include "reference/metric/bounding_volumes.h"
#include "shadowcts/case.h"

namespace shadowcts::metric {

struct LightFrame {
  bool directional = false;
  glm::dvec3 light_position{0.0};         // point light
  glm::dvec3 towards_light{0.0};          // directional: unit, from the scene towards the light
  glm::dvec3 plane_x{0.0}, plane_y{0.0};  // directional: orthonormal basis orthogonal to it
  double scale = 0.0;  // Case::scale(): every coordinate of the case is within [-scale, scale]
  // Distance by which every volume is enlarged before it is seen from the light: the watertight
  // triangle test is exact for a perturbation of the vertices by a few units of 2^-24 * scale
  // (segment_triangle.h), so a triangle it reports hit lies within ~2^-21 * scale of the exact
  // segment. 2^-18 * scale keeps every such triangle and leaves room for the rounding of the
  // double computations below.
  double margin = 0.0;
  // Tolerance of every comparison of distances computed in double: 1e-10 radians, or
  // 1e-10 * scale in the plane and along the light direction.
  double slack = 0.0;
  double depth_slack = 0.0;
};

LightFrame make_light_frame(const Case& c);
// The same for a caller that has the case's scale (Case::scale()) already.
LightFrame make_light_frame(const Case& c, double scale);

enum class CentreKind : std::uint8_t { point, segment };

struct LightSpaceElement {
  std::uint32_t cluster = 0;
  CentreKind centre = CentreKind::point;
  bool covers_everything = false;  // the light is inside the volume
  // Point light: unit directions from the light (the arc is arc(a, b)); directional: points of
  // the plane orthogonal to the light as (x, y, 0). A point centre is a.
  glm::dvec3 a{0.0}, b{0.0};
  GreatArc arc;         // point light, segment centre
  double radius = 0.0;  // angular or planar
  // Smallest light distance of the volume: |X - O| for a point light, -d . X for a directional
  // one (smaller is closer to the light). A sample closer to the light cannot be shadowed by it.
  double light_distance = 0.0;
};

LightSpaceElement make_light_space_element(const LightFrame& frame, const ClusterVolume& volume,
                                           std::uint32_t cluster);

// A view sample seen from the light: its direction from the light (point light, unit) or its
// position in the plane (directional), and its light distance.
struct LightSpaceQuery {
  glm::dvec3 position{0.0};
  double light_distance = 0.0;
  bool at_light = false;  // the sample is the point light itself: nothing can shadow it
};

LightSpaceQuery make_light_space_query(const LightFrame& frame, const glm::dvec3& sample);

// The pivot function of a tree node (section 5.4, step 1): the distance from the query to the
// pivot's centre minus the pivot's radius, so that it is <= 0 inside the pivot. -infinity when the
// pivot covers everything.
double pivot_distance(const LightFrame& frame, const LightSpaceElement& pivot,
                      const LightSpaceQuery& query);

// Bounds of pivot_distance over every query point in the element's region: the paper's d_near and
// d_far (section 5.2), made valid for segment centres by measuring the element's whole centre
// (the paper's formulas measure the centres' closest points). Unbounded when either covers
// everything.
struct DistanceBounds {
  double near = -std::numeric_limits<double>::infinity();
  double far = std::numeric_limits<double>::infinity();
};

DistanceBounds element_distance_bounds(const LightFrame& frame, const LightSpaceElement& pivot,
                                       const LightSpaceElement& element);

}  // namespace shadowcts::metric
