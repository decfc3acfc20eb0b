#pragma once
// The exact core of the soft-shadow oracle: area(unit disk ∩ union of convex polygons) with CGAL's
// General_polygon_set_2 and circle-segment traits over exact rationals. The only CGAL translation
// unit of the soft-shadow oracle (it costs ~16 s and ~1 GB to compile).
#include <vector>

#include "oracles/soft_shadow/sun_disk_projection.h"

namespace shadowcts {

struct CoveredDiskArea {
  double area = 0.0;       // of disk ∩ union, in [0, pi]
  bool fast_path = false;  // decided without the arrangement (nothing, or one polygon covers all)
};

// The polygons' double corners are taken exactly (as rationals) and replaced by their exact convex
// hull, so rounding in the projection can never produce a non-simple polygon. The arrangement is
// exact; the area is summed in double from its exact vertices by Green's theorem (line segments:
// the shoelace term; arcs of the unit circle: half the swept angle), with an error of a few ulps of
// pi per boundary curve.
CoveredDiskArea covered_disk_area(const std::vector<DiskPolygon>& polygons);

}  // namespace shadowcts
