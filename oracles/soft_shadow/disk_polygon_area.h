#pragma once
// Closed forms for one convex polygon against a disk centred at the origin, in double precision:
// the single-triangle oracle and the band-sensitivity bound use them.
#include "oracles/soft_shadow/sun_disk_projection.h"

namespace shadowcts {

// area(polygon ∩ unit disk), for any simple polygon (either orientation): the sum over its edges
// of the signed area of triangle(origin, edge) ∩ disk, each a closed form of circular sectors and
// one triangle (Green's theorem on a star-shaped disk).
double unit_disk_intersection_area(const DiskPolygon& polygon);

// The length of the polygon's boundary inside the closed disk of `radius` around the origin.
double boundary_length_in_disk(const DiskPolygon& polygon, double radius);

}  // namespace shadowcts
