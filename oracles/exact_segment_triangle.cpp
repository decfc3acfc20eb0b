#include "oracles/exact_segment_triangle.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/intersections.h>

namespace shadowcts {
namespace {

// Filtered exact predicates on double inputs: every query point handed to it is a double exactly.
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
// Exact rational coordinates, for the rare moved or far points that are not doubles.
using Rational = CGAL::Exact_rational;
using RationalKernel = CGAL::Simple_cartesian<Rational>;

// a + b, when the double sum is exact: Knuth's two-sum recovers the rounding error exactly
// (no overflow: the inputs are far inside double's range), and the sum is exact iff it is zero.
bool exact_double_sum(double a, double b, double& sum) {
  sum = a + b;
  if (!std::isfinite(sum)) return false;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  return (a - a_virtual) + (b - b_virtual) == 0.0;
}

// The exponent e of the power of two s = 2^e used to replace the directional ray from x by the
// segment [x, x + s d]. With i the largest |d_i|, s |d_i| >= 2 (bound + max|x|) (the factor 2
// absorbs the rounding of this computation), so for every t >= s the ray point has
// |x_i + t d_i| >= s |d_i| - |x_i| > bound: it lies outside the cube [-bound, bound]^3 that holds
// every triangle, and the segment meets a triangle iff the ray does.
int far_point_exponent(double scene_bound, double max_abs_x, const glm::dvec3& d) {
  const double max_abs_d = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
  const double need = 2.0 * (scene_bound + max_abs_x) / max_abs_d;
  if (!(need > 0.0)) return 0;
  int exponent = 0;
  std::frexp(need, &exponent);  // need = m 2^exponent with m in [0.5, 1): 2^exponent >= need
  return exponent;
}

template <class Kernel>
typename Kernel::Triangle_3 kernel_triangle(const Triangle& t) {
  using P = typename Kernel::Point_3;
  return {P(t.v0.x, t.v0.y, t.v0.z), P(t.v1.x, t.v1.y, t.v1.z), P(t.v2.x, t.v2.y, t.v2.z)};
}

// Segment (possibly a single point) against a non-degenerate triangle, in any CGAL kernel.
template <class Kernel>
bool triangle_meets_segment(const typename Kernel::Triangle_3& triangle,
                            const typename Kernel::Point_3& from,
                            const typename Kernel::Point_3& to) {
  if (from == to) return triangle.has_on(from);
  return CGAL::do_intersect(triangle, typename Kernel::Segment_3(from, to));
}

}  // namespace

bool is_zero_area(const Triangle& t) {
  using P = Epick::Point_3;
  return CGAL::collinear(P(t.v0.x, t.v0.y, t.v0.z), P(t.v1.x, t.v1.y, t.v1.z),
                         P(t.v2.x, t.v2.y, t.v2.z));
}

ExactShadowPredicate::ExactShadowPredicate(const HardShadowLight& light, double scene_bound)
    : light_(light), scene_bound_(scene_bound) {}

bool ExactShadowPredicate::blocks(const Triangle& t, const MovedPoint& x) const {
  if (is_zero_area(t)) return false;

  // Fast path: x (and, for a directional light, the far point) exactly in doubles.
  std::array<double, 3> moved{};
  bool exact = true;
  for (int i = 0; i < 3; ++i)
    exact = exact_double_sum(x.base[i], x.delta * x.direction[i], moved[i]) && exact;
  const double max_abs_x =
      std::max({std::fabs(x.base.x), std::fabs(x.base.y), std::fabs(x.base.z)}) + x.delta;
  const int far_exponent =
      light_.directional ? far_point_exponent(scene_bound_, max_abs_x, light_.direction) : 0;
  std::array<double, 3> far{};
  if (exact && light_.directional) {
    for (int i = 0; i < 3; ++i) {
      // Scaling a float by a power of two is exact in double at these exponents.
      const double step = std::ldexp(light_.direction[i], far_exponent);
      exact = exact_double_sum(moved[i], step, far[i]) && exact;
    }
  } else if (!light_.directional) {
    far = {light_.position.x, light_.position.y, light_.position.z};
  }
  if (exact) {
    using P = Epick::Point_3;
    return triangle_meets_segment<Epick>(kernel_triangle<Epick>(t), P(moved[0], moved[1], moved[2]),
                                         P(far[0], far[1], far[2]));
  }

  // Exact rational fallback: the same predicate on exactly constructed points.
  using P = RationalKernel::Point_3;
  using V = RationalKernel::Vector_3;
  const Rational delta(x.delta);
  const P from(Rational(x.base.x) + delta * x.direction.x,
               Rational(x.base.y) + delta * x.direction.y,
               Rational(x.base.z) + delta * x.direction.z);
  P to;
  if (light_.directional) {
    const Rational scale(std::ldexp(1.0, far_exponent));
    to = from + V(light_.direction.x, light_.direction.y, light_.direction.z) * scale;
  } else {
    to = P(light_.position.x, light_.position.y, light_.position.z);
  }
  return triangle_meets_segment<RationalKernel>(kernel_triangle<RationalKernel>(t), from, to);
}

}  // namespace shadowcts
