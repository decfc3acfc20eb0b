#include "shadowcts/geometry/exact_segment_triangle.h"

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
  int hits = 0, coplanar = 0;
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
