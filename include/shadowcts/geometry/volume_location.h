#pragma once
// Where a TOP-tree node files a triangle (partitioned shadow volumes), from the sides of its three
// vertices against the node's plane, for every psv build: reference, simd and device.
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

// positive / negative / on: some vertex lies strictly on that side or exactly on the plane.
// 1: the positive child; -1: the negative child (the closed negative side, a triangle in the plane
// included); 0: the intersection child, for a triangle that straddles the plane or touches an edge
// plane from its positive side. A query point on an edge plane goes to the negative child only, so
// every volume that can hold such a point must lie below the negative or the intersection child:
// the closed volume of a triangle with a vertex on the plane meets the plane (a ray through an
// edge shared with the node's triangle, or collinear with it, would leak otherwise). A capping
// plane's positive child holds no such volume that counts: a point on the capping plane within
// the edge planes is on the triangle.
SHADOWCTS_HD inline int volume_location(bool positive, bool negative, bool on, bool capping) {
  if (positive && negative) return 0;
  if (positive && on && !capping) return 0;
  return positive ? 1 : -1;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
