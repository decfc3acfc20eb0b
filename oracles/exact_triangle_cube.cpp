#include "oracles/exact_triangle_cube.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Iso_cuboid_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/intersections.h>

#include "oracles/exact_double_sum.h"

namespace shadowcts {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using RationalKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;

template <class Kernel>
typename Kernel::Triangle_3 kernel_triangle(const Triangle& t) {
  using P = typename Kernel::Point_3;
  return {P(t.v0.x, t.v0.y, t.v0.z), P(t.v1.x, t.v1.y, t.v1.z), P(t.v2.x, t.v2.y, t.v2.z)};
}

}  // namespace

bool triangle_meets_cube(const Triangle& t, const glm::dvec3& centre, double half_width) {
  double lo[3], hi[3];
  bool exact = true;
  for (int k = 0; k < 3; ++k) {
    exact = exact_double_sum(centre[k], -half_width, lo[k]) && exact;
    exact = exact_double_sum(centre[k], half_width, hi[k]) && exact;
  }
  if (exact) {
    using P = Epick::Point_3;
    return CGAL::do_intersect(kernel_triangle<Epick>(t),
                              Epick::Iso_cuboid_3(P(lo[0], lo[1], lo[2]), P(hi[0], hi[1], hi[2])));
  }
  // Bounds that are not doubles: built in exact rationals, never rounded.
  using FT = RationalKernel::FT;
  using P = RationalKernel::Point_3;
  const FT h(half_width);
  const P low(FT(centre.x) - h, FT(centre.y) - h, FT(centre.z) - h);
  const P high(FT(centre.x) + h, FT(centre.y) + h, FT(centre.z) + h);
  return CGAL::do_intersect(kernel_triangle<RationalKernel>(t),
                            RationalKernel::Iso_cuboid_3(low, high));
}

}  // namespace shadowcts
