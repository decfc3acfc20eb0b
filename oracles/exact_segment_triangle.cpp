#include "oracles/exact_segment_triangle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Iso_cuboid_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/intersections.h>

#include "oracles/exact_double_sum.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

// Filtered exact predicates on double inputs: every query point handed to it is a double exactly.
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
// Exact rational coordinates, for the rare moved or far points that are not doubles.
using Rational = CGAL::Exact_rational;
using RationalKernel = CGAL::Simple_cartesian<Rational>;

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

// The query of x in exact rationals: from x to the point light, or to x + 2^e d, beyond every
// caster (far_point_exponent).
std::pair<RationalKernel::Point_3, RationalKernel::Point_3> rational_query(
    const HardShadowLight& light, double scene_bound, const MovedPoint& x) {
  using P = RationalKernel::Point_3;
  using V = RationalKernel::Vector_3;
  const Rational delta(x.delta);
  const P from(Rational(x.base.x) + delta * x.direction.x,
               Rational(x.base.y) + delta * x.direction.y,
               Rational(x.base.z) + delta * x.direction.z);
  if (!light.directional) return {from, P(light.position.x, light.position.y, light.position.z)};
  const double max_abs_x =
      std::max({std::fabs(x.base.x), std::fabs(x.base.y), std::fabs(x.base.z)}) + x.delta;
  const Rational scale(
      std::ldexp(1.0, far_point_exponent(scene_bound, max_abs_x, light.direction)));
  return {from, from + V(light.direction.x, light.direction.y, light.direction.z) * scale};
}

}  // namespace

bool oracle_casts_shadow(const Case& c, std::size_t i) {
  const Triangle& t = c.triangles[i];
  if (t.mesh >= c.meshes.size())
    throw InputError(c.source, "triangles[" + std::to_string(i) + "].mesh",
                     "mesh id " + std::to_string(t.mesh) + " out of range");
  return c.meshes[t.mesh].caster && !is_zero_area(t);
}

bool is_zero_area(const Triangle& t) {
  using P = Epick::Point_3;
  return CGAL::collinear(P(t.v0.x, t.v0.y, t.v0.z), P(t.v1.x, t.v1.y, t.v1.z),
                         P(t.v2.x, t.v2.y, t.v2.z));
}

int exact_orientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d) {
  using P = Epick::Point_3;
  return int(
      CGAL::orientation(P(a.x, a.y, a.z), P(b.x, b.y, b.z), P(c.x, c.y, c.z), P(d.x, d.y, d.z)));
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
  const auto [from, to] = rational_query(light_, scene_bound_, x);
  return triangle_meets_segment<RationalKernel>(kernel_triangle<RationalKernel>(t), from, to);
}

namespace {

using RationalPoint = RationalKernel::Point_3;

RationalPoint rational_point(const glm::dvec3& x) {
  return RationalPoint(x.x, x.y, x.z);
}

// det[b - a, c - a, d] for a direction d: exact (filtered doubles where the differences are
// exact, which they are for float vertices of similar magnitude; rationals otherwise).
int orientation_towards(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                        const glm::dvec3& d) {
  std::array<double, 3> u{}, v{};
  bool exact = true;
  for (int i = 0; i < 3; ++i) {
    exact = exact_double_sum(b[i], -a[i], u[std::size_t(i)]) && exact;
    exact = exact_double_sum(c[i], -a[i], v[std::size_t(i)]) && exact;
  }
  if (exact) {
    using V = Epick::Vector_3;
    return int(CGAL::orientation(V(u[0], u[1], u[2]), V(v[0], v[1], v[2]), V(d.x, d.y, d.z)));
  }
  using V = RationalKernel::Vector_3;
  const RationalPoint pa = rational_point(a);
  return int(CGAL::orientation(rational_point(b) - pa, rational_point(c) - pa, V(d.x, d.y, d.z)));
}

// The side of x: +1 strictly on the light's side of the receiver's plane, 0 in it, -1 beyond.
template <class Point>
int side_of(const ReceiverPlane& plane, const Point& x) {
  const Point a(plane.a.x, plane.a.y, plane.a.z), b(plane.b.x, plane.b.y, plane.b.z),
      c(plane.c.x, plane.c.y, plane.c.z);
  return int(CGAL::orientation(a, b, c, x)) * plane.light_side;
}

int side_of_vertex(const ReceiverPlane& plane, const glm::vec3& v) {
  // A vertex the caster shares with the receiver lies in its plane: the receiver's neighbours
  // would otherwise send every such exact zero through CGAL's filters to exact arithmetic.
  const glm::dvec3 x(v);
  if (x == plane.a || x == plane.b || x == plane.c) return 0;
  return side_of(plane, Epick::Point_3(x.x, x.y, x.z));
}

using Interval = CGAL::Interval_nt<>;  // rounding-safe interval arithmetic

// det[b - a, c - a, d] and det[b - a, c - a, x - a] in intervals.
Interval interval_det(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const std::array<Interval, 3>& w) {
  std::array<Interval, 3> u, v;
  for (int i = 0; i < 3; ++i) {
    u[std::size_t(i)] = Interval(b[i]) - Interval(a[i]);
    v[std::size_t(i)] = Interval(c[i]) - Interval(a[i]);
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

Interval interval_orientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                              const glm::dvec3& x) {
  return interval_det(a, b, c,
                      {Interval(x.x) - Interval(a.x), Interval(x.y) - Interval(a.y),
                       Interval(x.z) - Interval(a.z)});
}

Interval interval_towards(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                          const glm::dvec3& d) {
  return interval_det(a, b, c, {Interval(d.x), Interval(d.y), Interval(d.z)});
}

// The rule's side for a straddling caster that meets the query of x at one point, decided in
// interval arithmetic where the intervals decide it: with g the caster's orientation and f the
// receiver's (positive on the light's side), the crossing of the caster's plane has
// f = (g(x) f(L) - f(x) g(L)) / (g(x) - g(L)), or f(x) - g(x) Df / Dg towards a direction d.
// Empty where an interval holds 0 or x is not a double (the exact construction decides then).
std::optional<bool> hit_side_by_intervals(const HardShadowLight& light, const ReceiverPlane& plane,
                                          const Triangle& t, const MovedPoint& x) {
  std::array<double, 3> moved{};
  for (int i = 0; i < 3; ++i)
    if (!exact_double_sum(x.base[i], x.delta * x.direction[i], moved[std::size_t(i)]))
      return std::nullopt;
  const glm::dvec3 p(moved[0], moved[1], moved[2]);
  const glm::dvec3 v0(t.v0), v1(t.v1), v2(t.v2);
  const Interval side(double(plane.light_side));
  const Interval fp = interval_orientation(plane.a, plane.b, plane.c, p) * side;
  const Interval gp = interval_orientation(v0, v1, v2, p);
  Interval numerator, denominator;
  if (!light.directional) {
    const Interval fl = interval_orientation(plane.a, plane.b, plane.c, light.position) * side;
    const Interval gl = interval_orientation(v0, v1, v2, light.position);
    numerator = gp * fl - fp * gl;
    denominator = gp - gl;
  } else {
    const Interval df = interval_towards(plane.a, plane.b, plane.c, light.direction) * side;
    const Interval dg = interval_towards(v0, v1, v2, light.direction);
    numerator = fp * dg - gp * df;
    denominator = dg;
  }
  if (!CGAL::is_certain(CGAL::sign(numerator) != CGAL::ZERO) ||
      !CGAL::is_certain(CGAL::sign(denominator) != CGAL::ZERO))
    return std::nullopt;
  const int s = int(CGAL::sign(numerator)) * int(CGAL::sign(denominator));
  return s > 0;
}

}  // namespace

ReceiverPlane ExactShadowPredicate::receiver_plane(const Triangle& receiver) const {
  ReceiverPlane plane;
  if (is_zero_area(receiver)) return plane;
  plane.active = true;
  plane.a = glm::dvec3(receiver.v0);
  plane.b = glm::dvec3(receiver.v1);
  plane.c = glm::dvec3(receiver.v2);
  if (light_.directional) {
    plane.light_side = orientation_towards(plane.a, plane.b, plane.c, light_.direction);
  } else {
    using P = Epick::Point_3;
    const glm::dvec3& l = light_.position;
    plane.light_side = int(CGAL::orientation(P(plane.a.x, plane.a.y, plane.a.z),
                                             P(plane.b.x, plane.b.y, plane.b.z),
                                             P(plane.c.x, plane.c.y, plane.c.z), P(l.x, l.y, l.z)));
  }
  return plane;
}

PlaneReach ExactShadowPredicate::reach(const ReceiverPlane& plane, const Triangle& t) const {
  if (!plane.active) return PlaneReach::whole;
  if (plane.light_side == 0) return PlaneReach::none;
  const int s0 = side_of_vertex(plane, t.v0), s1 = side_of_vertex(plane, t.v1),
            s2 = side_of_vertex(plane, t.v2);
  if (s0 > 0 && s1 > 0 && s2 > 0) return PlaneReach::whole;
  if (s0 <= 0 && s1 <= 0 && s2 <= 0) return PlaneReach::none;
  return PlaneReach::straddles;
}

bool ExactShadowPredicate::blocks(const Triangle& t, const MovedPoint& x,
                                  const ReceiverPlane& plane, PlaneReach reach) const {
  if (reach == PlaneReach::none || !blocks(t, x)) return false;
  if (reach == PlaneReach::whole) return true;
  if (const std::optional<bool> side = hit_side_by_intervals(light_, plane, t, x)) return *side;
  // A straddling caster: the part of t that meets the query, constructed in exact rationals (a
  // point, or a segment when the query lies in t's plane); the receiver's orientation is linear
  // along it, so one of its end points is strictly on the light's side iff some point is.
  const auto [from, to] = rational_query(light_, scene_bound_, x);
  if (from == to) return side_of(plane, from) > 0;
  const auto hit =
      CGAL::intersection(kernel_triangle<RationalKernel>(t), RationalKernel::Segment_3(from, to));
  if (!hit) return false;
  if (const RationalPoint* point = boost::get<RationalPoint>(&*hit))
    return side_of(plane, *point) > 0;
  if (const auto* piece = boost::get<RationalKernel::Segment_3>(&*hit))
    return side_of(plane, piece->source()) > 0 || side_of(plane, piece->target()) > 0;
  return false;
}

}  // namespace shadowcts

namespace shadowcts {
namespace {

// x - y when the double difference is exact.
bool exact_double_difference(double x, double y, double& difference) {
  return exact_double_sum(x, -y, difference);
}

// The sign of det(b - a, d, x - a) for a directional light: exact.
int directional_plane_side(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& d,
                           const glm::dvec3& x) {
  std::array<double, 3> u{}, w{};
  bool exact = true;
  for (int i = 0; i < 3; ++i) {
    exact = exact_double_difference(b[i], a[i], u[i]) && exact;
    exact = exact_double_difference(x[i], a[i], w[i]) && exact;
  }
  if (exact) {
    using V = Epick::Vector_3;
    return int(CGAL::orientation(V(u[0], u[1], u[2]), V(d.x, d.y, d.z), V(w[0], w[1], w[2])));
  }
  using P = RationalKernel::Point_3;
  using V = RationalKernel::Vector_3;
  const P pa(a.x, a.y, a.z);
  return int(CGAL::orientation(P(b.x, b.y, b.z) - pa, V(d.x, d.y, d.z), P(x.x, x.y, x.z) - pa));
}

// p - h (side 0) or p + h (side 1), rounded outwards where the double result is not exact.
double outward_bound(double p, double h, int side) {
  double bound = 0.0;
  if (side == 0) {
    if (!exact_double_sum(p, -h, bound)) bound = std::nextafter(bound, -HUGE_VAL);
  } else {
    if (!exact_double_sum(p, h, bound)) bound = std::nextafter(bound, HUGE_VAL);
  }
  return bound;
}

// The cube B (bounds rounded outwards) and its light hull H in one kernel. Corner c has the upper
// bound along axis k where bit k of c is set.
template <class Kernel>
struct CubeGeometry {
  using K = Kernel;
  using FT = typename Kernel::FT;
  using P = typename Kernel::Point_3;
  using Segment = typename Kernel::Segment_3;
  using KTriangle = typename Kernel::Triangle_3;

  struct Lateral {
    int c0 = 0, c1 = 0;                         // the silhouette edge, from corner c0 to c1
    CGAL::Orientation inside = CGAL::COPLANAR;  // the side of the lateral plane that holds B
  };

  bool directional = false;
  P light;                            // point light
  std::array<double, 3> direction{};  // directional light: d
  P centre;                           // strictly inside B
  typename Kernel::Iso_cuboid_3 box;
  std::array<double, 3> lo{}, hi{};
  std::array<P, 8> corner;
  std::array<P, 8> far;         // directional: corner + 2^e d, beyond the scene bound
  bool faces_light[3][2] = {};  // face (axis, 0 lower / 1 upper) faces the light
  std::array<Lateral, 12> laterals;
  int lateral_count = 0;
  bool silhouette_corner[8] = {};

  P point(const glm::dvec3& x) const { return P(x.x, x.y, x.z); }

  // A point from x towards the light: L, or x + d (none where that is not exact here).
  std::optional<P> towards_light(const P& x) const {
    if (!directional) return light;
    if constexpr (std::is_same_v<Kernel, Epick>) {
      std::array<double, 3> sum{};
      for (int k = 0; k < 3; ++k)
        if (!exact_double_sum(x[k], direction[std::size_t(k)], sum[std::size_t(k)]))
          return std::nullopt;
      return P(sum[0], sum[1], sum[2]);
    } else {
      return x + typename Kernel::Vector_3(direction[0], direction[1], direction[2]);
    }
  }

  // The plane of lateral face e (through L and the edge, or through the edge parallel to d).
  CGAL::Orientation lateral_side(const Lateral& e, const P& x) const {
    return directional ? CGAL::orientation(corner[e.c0], corner[e.c1], far[e.c1], x)
                       : CGAL::orientation(light, corner[e.c0], corner[e.c1], x);
  }

  bool lateral_meets(const Lateral& e, const Segment& s) const {
    if (!directional) return CGAL::do_intersect(KTriangle(light, corner[e.c0], corner[e.c1]), s);
    return CGAL::do_intersect(KTriangle(corner[e.c0], corner[e.c1], far[e.c1]), s) ||
           CGAL::do_intersect(KTriangle(corner[e.c0], far[e.c1], far[e.c0]), s);
  }

  // x in H: inside every face of B that does not face the light, and inside every lateral face.
  bool hull_contains(const P& x) const {
    for (int k = 0; k < 3; ++k) {
      if (!faces_light[k][0] && x[k] < FT(lo[k])) return false;
      if (!faces_light[k][1] && x[k] > FT(hi[k])) return false;
    }
    for (int i = 0; i < lateral_count; ++i) {
      const CGAL::Orientation side = lateral_side(laterals[i], x);
      if (side != CGAL::COPLANAR && side != laterals[i].inside) return false;
    }
    return true;
  }

  // A segment meets the closed convex H iff an end point lies in it or it crosses H's boundary:
  // a face of B (then it meets B) or a lateral face.
  bool segment_meets_hull(const P& a, const P& b) const {
    if (hull_contains(a) || hull_contains(b)) return true;
    const Segment s(a, b);
    if (CGAL::do_intersect(s, box)) return true;
    for (int i = 0; i < lateral_count; ++i)
      if (lateral_meets(laterals[i], s)) return true;
    return false;
  }

  // Whether all 8 corners lie strictly on the given side of the plane (a, b, c): then B misses
  // the closed other side.
  bool corners_strictly_on(const P& a, const P& b, const P& c, CGAL::Orientation side) const {
    for (const P& x : corner)
      if (CGAL::orientation(a, b, c, x) != side) return false;
    return true;
  }

  // A triangle meets the closed convex H iff the polygon T n H is not empty; each of its vertices
  // is a vertex of T in H, a crossing of an edge of T with the boundary of H (a face of B, so T
  // meets B, or a lateral face), or a crossing of an edge of H with T (an edge of B, so T meets B,
  // or a lateral edge from a silhouette corner).
  bool triangle_meets_hull(const Triangle& t) const {
    const std::array<P, 3> v = {point(glm::dvec3(t.v0)), point(glm::dvec3(t.v1)),
                                point(glm::dvec3(t.v2))};
    const KTriangle triangle(v[0], v[1], v[2]);
    // Quick exact rejections by the planes of V_T: its supporting plane (V_T lies on the side
    // away from the light) and the three planes through an edge and the light (V_T lies on the
    // third vertex's side). Each plane is spanned by T's vertices and a point towards the light:
    // L, or a vertex plus d (skipped where that sum is not exact in this kernel).
    std::array<std::optional<P>, 3> towards;
    for (int i = 0; i < 3; ++i) towards[std::size_t(i)] = towards_light(v[std::size_t(i)]);
    if (towards[0]) {
      const CGAL::Orientation light_side = CGAL::orientation(v[0], v[1], v[2], *towards[0]);
      if (light_side != CGAL::COPLANAR && corners_strictly_on(v[0], v[1], v[2], light_side))
        return false;
    }
    for (std::size_t i = 0; i < 3; ++i) {
      if (!towards[i]) continue;
      const P& a = v[i];
      const P& b = v[(i + 1) % 3];
      const CGAL::Orientation inner = CGAL::orientation(*towards[i], a, b, v[(i + 2) % 3]);
      if (inner != CGAL::COPLANAR && corners_strictly_on(*towards[i], a, b, CGAL::opposite(inner)))
        return false;
    }
    for (int c = 0; c < 8; ++c) {
      if (!silhouette_corner[c]) continue;
      if (directional) {
        if (CGAL::do_intersect(triangle, Segment(corner[c], far[c]))) return true;
      } else if (corner[c] != light && CGAL::do_intersect(triangle, Segment(corner[c], light))) {
        return true;
      }
    }
    if (CGAL::do_intersect(triangle, box)) return true;
    for (const P& x : v)
      if (hull_contains(x)) return true;
    for (int i = 0; i < 3; ++i) {
      const Segment edge(v[i], v[(i + 1) % 3]);
      for (int e = 0; e < lateral_count; ++e)
        if (lateral_meets(laterals[e], edge)) return true;
    }
    return false;
  }
};

// Builds the geometry; false when a needed point is not exact in this kernel (doubles only).
template <class Kernel>
bool build_cube(const HardShadowLight& light, double scene_bound, const glm::dvec3& centre,
                double half_width, CubeGeometry<Kernel>& g) {
  using P = typename Kernel::Point_3;
  g.directional = light.directional;
  g.direction = {light.direction.x, light.direction.y, light.direction.z};
  g.centre = P(centre.x, centre.y, centre.z);
  double max_abs = 0.0;
  for (int k = 0; k < 3; ++k) {
    g.lo[k] = outward_bound(centre[k], half_width, 0);
    g.hi[k] = outward_bound(centre[k], half_width, 1);
    max_abs = std::max({max_abs, std::fabs(g.lo[k]), std::fabs(g.hi[k])});
  }
  g.box = typename Kernel::Iso_cuboid_3(P(g.lo[0], g.lo[1], g.lo[2]), P(g.hi[0], g.hi[1], g.hi[2]));
  for (int c = 0; c < 8; ++c)
    g.corner[std::size_t(c)] =
        P((c & 1) ? g.hi[0] : g.lo[0], (c & 2) ? g.hi[1] : g.lo[1], (c & 4) ? g.hi[2] : g.lo[2]);
  if (light.directional) {
    for (int k = 0; k < 3; ++k) {
      g.faces_light[k][0] = light.direction[k] < 0.0;
      g.faces_light[k][1] = light.direction[k] > 0.0;
    }
  } else {
    g.light = P(light.position.x, light.position.y, light.position.z);
    for (int k = 0; k < 3; ++k) {
      g.faces_light[k][0] = light.position[k] < g.lo[k];
      g.faces_light[k][1] = light.position[k] > g.hi[k];
    }
  }
  // Silhouette edges: between a face that faces the light and one that does not. (An edge whose
  // line holds L has L in the planes of both its faces, so neither faces the light: every
  // lateral face is a proper triangle. Likewise an edge parallel to d lies between two faces
  // parallel to d.)
  g.lateral_count = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (int si = 0; si < 2; ++si)
      for (int sj = 0; sj < 2; ++sj) {
        if (g.faces_light[i][si] == g.faces_light[j][sj]) continue;
        typename CubeGeometry<Kernel>::Lateral e;
        e.c0 = (si << i) | (sj << j);
        e.c1 = e.c0 | (1 << k);
        g.laterals[std::size_t(g.lateral_count++)] = e;
        g.silhouette_corner[e.c0] = g.silhouette_corner[e.c1] = true;
      }
  }
  if (light.directional) {
    const int exponent = far_point_exponent(scene_bound, max_abs, light.direction);
    for (int c = 0; c < 8; ++c) {
      if (!g.silhouette_corner[c]) continue;
      const P& x = g.corner[std::size_t(c)];
      if constexpr (std::is_same_v<Kernel, Epick>) {
        std::array<double, 3> f{};
        for (int k = 0; k < 3; ++k)
          if (!exact_double_sum(x[k], std::ldexp(light.direction[k], exponent), f[k])) return false;
        g.far[std::size_t(c)] = P(f[0], f[1], f[2]);
      } else {
        g.far[std::size_t(c)] =
            x + typename Kernel::Vector_3(light.direction.x, light.direction.y, light.direction.z) *
                    typename Kernel::FT(std::ldexp(1.0, exponent));
      }
    }
  }
  for (int i = 0; i < g.lateral_count; ++i) {
    auto& e = g.laterals[std::size_t(i)];
    e.inside = g.lateral_side(e, g.centre);
  }
  return true;
}

}  // namespace

int ExactShadowPredicate::light_plane_side(const glm::dvec3& a, const glm::dvec3& b,
                                           const glm::dvec3& x) const {
  if (light_.directional) return directional_plane_side(a, b, light_.direction, x);
  using P = Epick::Point_3;
  const glm::dvec3& l = light_.position;
  return int(
      CGAL::orientation(P(l.x, l.y, l.z), P(a.x, a.y, a.z), P(b.x, b.y, b.z), P(x.x, x.y, x.z)));
}

struct ExactCubeQuery::Impl {
  std::optional<CubeGeometry<Epick>> fast;
  std::optional<CubeGeometry<RationalKernel>> exact;  // built where fast fails, or on demand
  // A lateral face that came out degenerate (impossible by the construction; kept as a guard):
  // every test then answers "meets", which is conservative.
  bool everything_meets = false;
  HardShadowLight light;
  double scene_bound = 0.0;
  glm::dvec3 centre{0.0};
  double half_width = 0.0;

  void check(const auto& g) {
    for (int i = 0; i < g.lateral_count; ++i)
      if (g.laterals[std::size_t(i)].inside == CGAL::COPLANAR) everything_meets = true;
  }

  template <class F>
  bool visit(F&& f) const {
    if (everything_meets) return true;
    return fast ? f(*fast) : f(*exact);
  }

  // The geometry in exact rationals, for queries on points that are not doubles.
  const CubeGeometry<RationalKernel>& exact_geometry() {
    if (!exact) {
      exact.emplace();
      build_cube(light, scene_bound, centre, half_width, *exact);
      check(*exact);
    }
    return *exact;
  }
};

ExactCubeQuery::ExactCubeQuery(const ExactShadowPredicate& predicate, const glm::dvec3& centre,
                               double half_width)
    : impl_(std::make_unique<Impl>()) {
  impl_->light = predicate.light();
  impl_->scene_bound = predicate.scene_bound();
  impl_->centre = centre;
  impl_->half_width = half_width;
  impl_->fast.emplace();
  if (build_cube(predicate.light(), predicate.scene_bound(), centre, half_width, *impl_->fast)) {
    impl_->check(*impl_->fast);
    return;
  }
  impl_->fast.reset();
  impl_->exact_geometry();
}

ExactCubeQuery::~ExactCubeQuery() = default;

bool ExactCubeQuery::meets_triangle(const Triangle& t) const {
  return impl_->visit([&](const auto& g) {
    using Kernel = typename std::decay_t<decltype(g)>::K;
    return CGAL::do_intersect(kernel_triangle<Kernel>(t), g.box);
  });
}

bool ExactCubeQuery::shadow_ray_meets(const glm::dvec3& x) const {
  return impl_->visit([&](const auto& g) { return g.hull_contains(g.point(x)); });
}

bool ExactCubeQuery::shadow_wedge_meets(const glm::dvec3& a, const glm::dvec3& b) const {
  return impl_->visit([&](const auto& g) { return g.segment_meets_hull(g.point(a), g.point(b)); });
}

bool ExactCubeQuery::shadow_volume_meets(const Triangle& t) const {
  return impl_->visit([&](const auto& g) { return g.triangle_meets_hull(t); });
}

bool ExactCubeQuery::clip_wedge_meets(const Triangle& t, const ReceiverPlane& plane) const {
  // t n plane: its vertices in the plane and the crossings of its edges with it.
  const std::array<RationalPoint, 3> v = {rational_point(glm::dvec3(t.v0)),
                                          rational_point(glm::dvec3(t.v1)),
                                          rational_point(glm::dvec3(t.v2))};
  const RationalKernel::Plane_3 receiver(rational_point(plane.a), rational_point(plane.b),
                                         rational_point(plane.c));
  std::array<int, 3> side{};
  for (int i = 0; i < 3; ++i) side[std::size_t(i)] = side_of(plane, v[std::size_t(i)]);
  std::vector<RationalPoint> points;
  for (std::size_t i = 0; i < 3; ++i) {
    if (side[i] == 0) points.push_back(v[i]);
    const std::size_t j = (i + 1) % 3;
    if (side[i] * side[j] < 0) {
      const auto crossing = CGAL::intersection(RationalKernel::Segment_3(v[i], v[j]), receiver);
      if (crossing)
        if (const RationalPoint* x = boost::get<RationalPoint>(&*crossing)) points.push_back(*x);
    }
  }
  if (points.empty()) return false;
  if (impl_->everything_meets) return true;
  const CubeGeometry<RationalKernel>& g = impl_->exact_geometry();
  if (impl_->everything_meets) return true;
  // The piece is convex (a segment or a point): the wedge behind it is the union of the wedges
  // behind the segments between its points.
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i; j < points.size(); ++j) {
      const bool meets = points[i] == points[j] ? g.hull_contains(points[i])
                                                : g.segment_meets_hull(points[i], points[j]);
      if (meets) return true;
    }
  return false;
}

}  // namespace shadowcts
