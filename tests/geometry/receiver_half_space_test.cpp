#include "shadowcts/geometry/receiver_half_space.h"

#include <algorithm>
#include <optional>
#include <random>

#include <CGAL/Gmpq.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace shadowcts::geometry {
namespace {

using K = CGAL::Simple_cartesian<CGAL::Gmpq>;
using P = K::Point_3;

P point(const glm::dvec3& x) {
  return P(x.x, x.y, x.z);
}

glm::dvec3 float_point(const glm::dvec3& x) {
  return glm::dvec3(double(float(x.x)), double(float(x.y)), double(float(x.z)));
}

// The rule by exact constructions: the part of caster n segment (ray, cut far beyond the scene)
// strictly on the light's side of the receiver's plane is not empty.
bool rule_by_construction(const glm::dvec3 r[3], const glm::dvec3& p, const glm::dvec3& light,
                          bool directional, const glm::dvec3 t[3]) {
  const K::Plane_3 plane(point(r[0]), point(r[1]), point(r[2]));
  const P far = directional ? point(p) + K::Vector_3(light.x, light.y, light.z) * K::FT(1 << 20)
                            : point(light);
  const CGAL::Oriented_side light_side =
      directional ? plane.oriented_side(point(r[0]) + K::Vector_3(light.x, light.y, light.z))
                  : plane.oriented_side(far);
  const K::Triangle_3 caster(point(t[0]), point(t[1]), point(t[2]));
  const auto hit = CGAL::intersection(caster, K::Segment_3(point(p), far));
  if (!hit) return false;
  if (const P* x = boost::get<P>(&*hit)) return plane.oriented_side(*x) == light_side;
  return false;  // the segment lies in the caster's plane: documented as never counting
}

bool meets(const glm::dvec3& p, const glm::dvec3& light, bool directional, const glm::dvec3 t[3]) {
  const P far = directional ? point(p) + K::Vector_3(light.x, light.y, light.z) * K::FT(1 << 20)
                            : point(light);
  return CGAL::do_intersect(K::Triangle_3(point(t[0]), point(t[1]), point(t[2])),
                            K::Segment_3(point(p), far));
}

glm::dvec3 f(float x, float y, float z) {
  return glm::dvec3(x, y, z);
}

TEST(ReceiverHalfSpace, CoplanarNeighbourAndConvexNextFaceNeverCount) {
  const glm::dvec3 light = f(0.3f, 5.0f, 0.2f);
  // Receiver and its coplanar neighbour in the floor y = 0.
  const ReceiverHalfSpace h = receiver_half_space(f(0, 0, 0), f(0, 0, 1), f(1, 0, 0), false, light);
  ASSERT_TRUE(h.has_plane);
  ASSERT_NE(h.light_side, 0);
  EXPECT_EQ(caster_reach(h, f(1, 0, 0), f(0, 0, 1), f(1, 0, 1)), CasterReach::no_hit);
  // The next face of a convex mesh bends down beyond the shared edge.
  EXPECT_EQ(caster_reach(h, f(1, 0, 0), f(0, 0, 1), f(1, -0.25f, 1)), CasterReach::no_hit);
  // A wall standing on the floor straddles: it counts where it rises above the floor.
  const glm::dvec3 wall[3] = {f(2, 0, -1), f(2, 0, 3), f(2, 3, 1)};
  EXPECT_EQ(caster_reach(h, wall[0], wall[1], wall[2]), CasterReach::straddles);
  const glm::dvec3 behind = f(2.5f, -1e-7f, 0.5f);  // below the floor
  const glm::dvec3 lamp = f(-3, 2, 0.5f);
  const ReceiverHalfSpace h2 = receiver_half_space(f(2, 0, 0), f(2, 0, 1), f(3, 0, 0), false, lamp);
  EXPECT_TRUE(caster_counts(h2, behind, wall[0], wall[1], wall[2]));
  // A light exactly in the receiver's plane: nothing is strictly on its side.
  const ReceiverHalfSpace grazing =
      receiver_half_space(f(0, 0, 0), f(0, 0, 1), f(1, 0, 0), false, f(4, 0, 4));
  EXPECT_TRUE(grazing.has_plane);
  EXPECT_EQ(grazing.light_side, 0);
  EXPECT_FALSE(caster_counts(grazing, f(0.25f, 0, 0.25f), wall[0], wall[1], wall[2]));
  // A zero-area receiver has no plane: the rule is void.
  const ReceiverHalfSpace line =
      receiver_half_space(f(0, 0, 0), f(1, 1, 1), f(2, 2, 2), false, light);
  EXPECT_FALSE(line.has_plane);
  EXPECT_TRUE(caster_counts(line, f(0, 0, 0), f(1, 0, 0), f(0, 0, 1), f(1, 0, 1)));
}

// A segment in the caster's plane that ends at a light inside the caster: shadowed under every
// move of the sample, so the rule must count it.
TEST(ReceiverHalfSpace, ASegmentInTheCastersPlaneCountsThroughALightInsideTheCaster) {
  const glm::dvec3 light = f(1, 1, 0);
  const ReceiverHalfSpace h =
      receiver_half_space(f(-8, -3, -8), f(-8, -3, 8), f(8, -3, 0), false, light);
  const glm::dvec3 caster[3] = {f(0, 0, 0), f(4, 0, 0), f(0, 4, 0)};  // in z = 0, holds L
  const glm::dvec3 p = f(1, -3, 0);                                   // in z = 0 too
  ASSERT_TRUE(meets(p, light, false, caster));
  EXPECT_EQ(caster_reach(h, caster[0], caster[1], caster[2]), CasterReach::every_hit);
  EXPECT_TRUE(hit_on_light_side(h, p, caster[0], caster[1], caster[2]));
  // The light outside the caster, still in its plane: only a move off the plane can tell.
  const glm::dvec3 beside = f(5, 1, 0);
  const ReceiverHalfSpace h2 =
      receiver_half_space(f(-8, -3, -8), f(-8, -3, 8), f(8, -3, 0), false, beside);
  EXPECT_FALSE(hit_on_light_side(h2, f(-1, -3, 0), caster[0], caster[1], caster[2]));
}

// Straddling casters through the shadow segments of samples within rounding of a tilted
// receiver: the shared predicate must agree with exact constructions on every hit.
TEST(ReceiverHalfSpace, HitSideAgreesWithExactConstructions) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int straddling_hits = 0, counted = 0;
  for (int i = 0; i < 6000; ++i) {
    const bool directional = i % 3 == 0;
    glm::dvec3 r[3];
    for (auto& v : r) v = float_point(glm::dvec3(u(rng), 0.1 * u(rng), u(rng)));
    // A float sample near the receiver's plane (rounded from a point of it).
    const double s = 0.3 * (u(rng) + 1.0), t = 0.3 * (u(rng) + 1.0);
    const glm::dvec3 p = float_point(r[0] + s * (r[1] - r[0]) + t * (r[2] - r[0]));
    const glm::dvec3 light = directional
                                 ? float_point(glm::dvec3(u(rng), 1.0 + u(rng) * 0.5, u(rng)))
                                 : float_point(glm::dvec3(2 * u(rng), 3.0 + u(rng), 2 * u(rng)));
    const ReceiverHalfSpace h = receiver_half_space(r[0], r[1], r[2], directional, light);
    if (!h.has_plane || h.light_side == 0) continue;
    // A caster through a point of the segment near where it crosses the receiver's plane (the
    // sample is within rounding of the plane, on either side).
    const glm::dvec3 towards = directional ? light : light - p;
    const glm::dvec3 normal = glm::cross(r[1] - r[0], r[2] - r[0]);
    const double crossing = -glm::dot(normal, p - r[0]) / glm::dot(normal, towards);
    const double along = std::max(0.0, crossing + std::ldexp(u(rng), -20 - int(rng() % 20)));
    const glm::dvec3 x = p + along * towards;
    glm::dvec3 c[3];
    // x is the centroid (up to the vertices' rounding to float).
    const glm::dvec3 e0 = 0.05 * glm::dvec3(u(rng), u(rng), u(rng));
    const glm::dvec3 e1 = 0.05 * glm::dvec3(u(rng), u(rng), u(rng));
    c[0] = float_point(x + e0);
    c[1] = float_point(x + e1);
    c[2] = float_point(x - e0 - e1);
    if (i % 5 == 0) c[0] = r[0];  // sharing a receiver vertex, in its plane
    if (!meets(p, light, directional, c)) continue;
    if (caster_reach(h, c[0], c[1], c[2]) != CasterReach::straddles) continue;
    ++straddling_hits;
    const bool expected = rule_by_construction(r, p, light, directional, c);
    counted += expected;
    ASSERT_EQ(hit_on_light_side(h, p, c[0], c[1], c[2]), expected) << i;
  }
  EXPECT_GT(straddling_hits, 500);
  EXPECT_GT(counted, 50);
  EXPECT_LT(counted, straddling_hits - 50);
}

}  // namespace
}  // namespace shadowcts::geometry
