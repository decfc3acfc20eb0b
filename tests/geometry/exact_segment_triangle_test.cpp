#include "shadowcts/geometry/exact_segment_triangle.h"

#include "shadowcts/geometry/segment_box.h"

#include <cmath>
#include <random>

#include <CGAL/Gmpq.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

namespace shadowcts::geometry {
namespace {

using K = CGAL::Simple_cartesian<CGAL::Gmpq>;
using P = K::Point_3;

P point(const glm::dvec3& x) {
  return P(x.x, x.y, x.z);
}

// CGAL's exact answer for the closed segment (or the ray, cut far beyond the grid's cube).
bool cgal_meets(const glm::dvec3& p, const glm::dvec3& light, bool directional, const glm::dvec3& a,
                const glm::dvec3& b, const glm::dvec3& c) {
  const K::Triangle_3 t(point(a), point(b), point(c));
  if (t.is_degenerate()) return false;
  const P far = directional ? point(p) + K::Vector_3(light.x, light.y, light.z) * K::FT(1 << 20)
                            : point(light);
  return CGAL::do_intersect(t, K::Segment_3(point(p), far));
}

// Points of a coarse grid: coplanar, collinear and on-edge configurations are frequent, and every
// coordinate is exact.
glm::dvec3 grid_point(std::mt19937& rng) {
  std::uniform_int_distribution<int> coordinate(-2, 2);
  return glm::dvec3(coordinate(rng), coordinate(rng), coordinate(rng)) * 0.5;
}

glm::dvec3 float_point(std::mt19937& rng) {
  std::uniform_real_distribution<float> coordinate(-2.0f, 2.0f);
  return glm::dvec3(coordinate(rng), coordinate(rng), coordinate(rng));
}

void expect_agreement(std::mt19937& rng, glm::dvec3 (*make)(std::mt19937&), int trials) {
  int hits = 0, coplanar = 0, boxes_apart = 0;
  for (int n = 0; n < trials; ++n) {
    const glm::dvec3 a = make(rng), b = make(rng), c = make(rng), p = make(rng);
    glm::dvec3 q = make(rng);
    const bool directional = n % 2 == 1;
    if (directional && q == glm::dvec3(0.0)) q = glm::dvec3(0.0, 1.0, 0.0);
    if (!directional && q == p) continue;  // a sample at the light: no segment
    const bool expected = cgal_meets(p, q, directional, a, b, c);
    const bool got =
        directional ? ray_meets_triangle(p, q, a, b, c) : segment_meets_triangle(p, q, a, b, c);
    hits += expected;
    // The box prefilter of the brute-force backends (segment_box.h) may only drop what misses:
    // the points are floats, so the boxes are exact.
    const bool boxes_meet = boxes_overlap(triangle_box(glm::vec3(a), glm::vec3(b), glm::vec3(c)),
                                          segment_box(glm::vec3(p), glm::vec3(q), directional));
    ASSERT_TRUE(boxes_meet || !expected) << "trial " << n << ": a meeting triangle's box dropped";
    boxes_apart += boxes_meet ? 0 : 1;
    coplanar += orientation(a, b, c, p) == 0 &&
                (directional ? orientation_towards(a, b, c, q) : orientation(a, b, c, q)) == 0;
    ASSERT_EQ(got, expected) << (directional ? "ray" : "segment") << " trial " << n << ": p ("
                             << p.x << ", " << p.y << ", " << p.z << ") q (" << q.x << ", " << q.y
                             << ", " << q.z << ") a (" << a.x << ", " << a.y << ", " << a.z
                             << ") b (" << b.x << ", " << b.y << ", " << b.z << ") c (" << c.x
                             << ", " << c.y << ", " << c.z << ")";
  }
  // The generator must exercise both answers and the coplanar paths.
  EXPECT_GT(hits, trials / 50);
  EXPECT_LT(hits, trials - trials / 50);
  EXPECT_GT(boxes_apart, trials / 50);
  if (make == grid_point) {
    EXPECT_GT(coplanar, trials / 200);
  }
}

TEST(ExactSegmentTriangle, AgreesWithCgalOnDegenerateGridConfigurations) {
  std::mt19937 rng(7);
  expect_agreement(rng, grid_point, 60000);
}

TEST(ExactSegmentTriangle, AgreesWithCgalOnRandomFloats) {
  std::mt19937 rng(11);
  expect_agreement(rng, float_point, 20000);
}

TEST(SegmentBox, ClosedAndUnboundedOnlyTowardsADirectionalLight) {
  const FloatBox point = segment_box({1, -2, 3}, {-1, 5, 3}, false);
  EXPECT_EQ(point.lo[0], -1.0f);
  EXPECT_EQ(point.hi[0], 1.0f);
  EXPECT_EQ(point.lo[1], -2.0f);
  EXPECT_EQ(point.hi[1], 5.0f);
  EXPECT_EQ(point.lo[2], 3.0f);
  EXPECT_EQ(point.hi[2], 3.0f);
  const FloatBox ray = segment_box({1, -2, 3}, {0.5f, -0.5f, 0.0f}, true);
  EXPECT_EQ(ray.lo[0], 1.0f);
  EXPECT_EQ(ray.hi[0], INFINITY);
  EXPECT_EQ(ray.lo[1], -INFINITY);
  EXPECT_EQ(ray.hi[1], -2.0f);
  EXPECT_EQ(ray.lo[2], 3.0f);  // no z component: the ray stays in its plane
  EXPECT_EQ(ray.hi[2], 3.0f);
  // A triangle whose box touches the segment's at one corner overlaps (closed boxes); one a float
  // step beyond does not.
  EXPECT_TRUE(boxes_overlap(triangle_box({1, 5, 3}, {2, 6, 3}, {2, 5, 4}), point));
  EXPECT_FALSE(
      boxes_overlap(triangle_box({1, std::nextafter(5.0f, 6.0f), 3}, {2, 6, 3}, {2, 6, 4}), point));
}

TEST(ExactSegmentTriangle, SharedEdgeIsClosedOnBothSidesAndVerticesCount) {
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(1, 1, 0);
  const glm::dvec3 light(0.5, 0.5, 3.0);
  // The segment through the shared edge (b, c) meets both triangles.
  EXPECT_TRUE(segment_meets_triangle(glm::dvec3(0.5, 0.5, -1.0), light, a, b, c));
  EXPECT_TRUE(segment_meets_triangle(glm::dvec3(0.5, 0.5, -1.0), light, b, d, c));
  // Ending exactly on a vertex, or starting on the face, counts (closed segment, closed triangle).
  EXPECT_TRUE(segment_meets_triangle(glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 0), a, b, c));
  EXPECT_TRUE(ray_meets_triangle(glm::dvec3(0.25, 0.25, 0), glm::dvec3(0, 0, 1), a, b, c));
  // A ray pointing away from the plane does not.
  EXPECT_FALSE(ray_meets_triangle(glm::dvec3(0.25, 0.25, 1), glm::dvec3(0, 0, 1), a, b, c));
  // Zero-area triangles never do.
  EXPECT_FALSE(segment_meets_triangle(glm::dvec3(0.5, 0, -1), glm::dvec3(0.5, 0, 1), a, b,
                                      glm::dvec3(2, 0, 0)));
}

}  // namespace
}  // namespace shadowcts::geometry
