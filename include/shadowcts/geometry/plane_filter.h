#pragma once
// The float filter of partitioned shadow volumes (reference/psv/plane_side.h), for host and
// device: a plane stored as four floats (rounded from the double-precision plane of a shadow
// volume), its value at a point in double, and a proven bound on the distance of that value from
// the exact plane's. Where |value| does not clear the bound an exact orientation predicate decides
// the side. The reference and the GPU port evaluate the same operations in the same order, one
// rounding each (rounded_arithmetic.h: nvcc must not fuse them), so their filters fail on the same
// points and their wedge tests agree to the bit.
#include <cmath>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

struct PlaneFilter {
  double scene_bound = 0.0;  // M: >= every |coordinate| of triangles, light and query points
  // The error of the double-precision plane itself (before rounding to float), added to every
  // bound: edge planes through the light, and capping planes (the triangle's own plane).
  double edge_extra_error = 0.0;
  double capping_extra_error = 0.0;
};

// The double-precision normal is within about 2^-48 M^2 of the exact one per component
// (differences, products and one subtraction, each rounded once); times a point of size 3 M, plus
// the same error through the offset, that is below 2^-45 M^3. 2^-40 covers it with room.
// Directional edge normals are (b - a) x d: M |d|_1 instead of M^2.
SHADOWCTS_HD inline PlaneFilter make_plane_filter(bool directional, const glm::dvec3& direction,
                                                  double scene_bound) {
  PlaneFilter f;
  f.scene_bound = scene_bound;
  const double m = scene_bound;
  const double d1 =
      rounded_add(rounded_add(fabs(direction.x), fabs(direction.y)), fabs(direction.z));
  f.capping_extra_error = rounded_mul(rounded_mul(rounded_mul(0x1p-40, m), m), m);
  f.edge_extra_error = directional ? rounded_mul(rounded_mul(rounded_mul(0x1p-40, m), m), d1)
                                   : f.capping_extra_error;
  return f;
}

// a x + b y + c z + d in double. Products of a float and a float-valued double are exact; three
// roundings remain.
SHADOWCTS_HD inline double plane_value(const float plane[4], const glm::dvec3& p) {
  return rounded_add(rounded_add(rounded_add(rounded_mul(double(plane[0]), p.x),
                                             rounded_mul(double(plane[1]), p.y)),
                                 rounded_mul(double(plane[2]), p.z)),
                     double(plane[3]));
}

// Bound on |plane_value - exact plane value at p|. Rounding the coefficients to float moves each
// by at most 2^-24 of itself, and the offset was computed as -n . L (or -n . a) with terms up to
// |n|_1 M: 2^-22 of those magnitudes bounds both and the evaluation's roundings; the extra term
// covers the double normal's own error. Below float's normal range (a scene scaled below about
// 2^-40: the offset is a product of three coordinates) rounding moves a coefficient by up to
// 2^-150 instead, whatever its size (the subnormal term). A coefficient beyond float's range is
// infinite, and so is the bound: the exact test decides.
SHADOWCTS_HD inline double plane_error_bound(const PlaneFilter& filter, const float plane[4],
                                             bool capping, const glm::dvec3& p) {
  const double a = fabs(double(plane[0])), b = fabs(double(plane[1])), c = fabs(double(plane[2])),
               d = fabs(double(plane[3]));
  const double px = fabs(p.x), py = fabs(p.y), pz = fabs(p.z);
  const double magnitude = rounded_add(
      rounded_add(
          rounded_add(rounded_add(rounded_mul(a, px), rounded_mul(b, py)), rounded_mul(c, pz)), d),
      rounded_mul(rounded_add(rounded_add(a, b), c), filter.scene_bound));
  const double subnormal_error =
      rounded_mul(0x1p-149, rounded_add(rounded_add(rounded_add(px, py), pz), 1.0));
  return rounded_add(rounded_add(rounded_mul(0x1p-22, magnitude), subnormal_error),
                     capping ? filter.capping_extra_error : filter.edge_extra_error);
}

// Upper bound on the light distance of the point p (a view sample), Mora 2016 section 3.3: for a
// point light |p - L| (differences, squares, sum and root: a relative error far below 2^-48); for
// a directional light d (towards the light) -d . p up to a constant, each dot product of float
// values rounding three times (2^-50 of the absolute terms bounds the error).
SHADOWCTS_HD inline double sample_light_depth(bool directional, const glm::dvec3& light,
                                              const glm::dvec3& p) {
  if (directional) {
    const double error = rounded_mul(
        0x1p-50,
        rounded_add(rounded_add(fabs(rounded_mul(light.x, p.x)), fabs(rounded_mul(light.y, p.y))),
                    fabs(rounded_mul(light.z, p.z))));
    const double dot =
        rounded_add(rounded_add(rounded_mul(light.x, p.x), rounded_mul(light.y, p.y)),
                    rounded_mul(light.z, p.z));
    return rounded_add(-dot, error);
  }
  const double x = rounded_sub(p.x, light.x), y = rounded_sub(p.y, light.y),
               z = rounded_sub(p.z, light.z);
  const double length2 =
      rounded_add(rounded_add(rounded_mul(x, x), rounded_mul(y, y)), rounded_mul(z, z));
  return rounded_mul(sqrt(length2), 1.0 + 0x1p-48);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
