#include "shadowcts/geometry/exact_orientation.h"

#include <cmath>
#include <random>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

namespace shadowcts::geometry {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

int cgal_orientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                     const glm::dvec3& d) {
  using P = Epick::Point_3;
  // CGAL's orientation(p, q, r, s) is the sign of det[q - p, r - p, s - p].
  return int(
      CGAL::orientation(P(a.x, a.y, a.z), P(b.x, b.y, b.z), P(c.x, c.y, c.z), P(d.x, d.y, d.z)));
}

glm::dvec3 float_point(const glm::dvec3& x) {
  return glm::dvec3(double(float(x.x)), double(float(x.y)), double(float(x.z)));
}

glm::dvec3 random_float_point(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double x = u(rng), y = u(rng), z = u(rng);
  return float_point(glm::dvec3(x, y, z) * scale);
}

TEST(ExactOrientation, AgreesWithCgalOnRandomAndNearlyCoplanarFloatPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int zeros = 0, exact_path = 0;
  for (int i = 0; i < 20000; ++i) {
    const double scale = std::ldexp(1.0, int(rng() % 40) - 20);
    const glm::dvec3 a = random_float_point(rng, scale), b = random_float_point(rng, scale),
                     c = random_float_point(rng, scale);
    glm::dvec3 d = random_float_point(rng, scale);
    if (i % 2 == 1) {
      // A rounded point of the plane: the filter cannot decide it, the expansions must.
      const double s = u(rng), t = u(rng);
      d = float_point(a + s * (b - a) + t * (c - a));
      ++exact_path;
    }
    if (i % 7 == 3) d = float_point(a + 0.5 * (b - a));  // often exactly on the line
    const int expected = cgal_orientation(a, b, c, d);
    zeros += expected == 0;
    ASSERT_EQ(orientation(a, b, c, d), expected) << i;
    ASSERT_EQ(sign(orientation_value(a, b, c, d)), expected) << i;
  }
  EXPECT_GT(zeros, 100);  // the degenerate answer was exercised
  EXPECT_GT(exact_path, 1000);
}

TEST(ExactOrientation, CoordinatesOfVeryDifferentMagnitudes) {
  // Points near the origin beside points at 1e7: the differences are not doubles' exact
  // operands in the filter, and the determinant spans many exponents.
  const glm::dvec3 a(glm::vec3(1e7f, 0.0f, 0.0f)), b(glm::vec3(1e7f, 1.0f, 1e-30f)),
      c(glm::vec3(1e-20f, 1e7f, 3.0f));
  std::mt19937_64 rng(3);
  for (int i = 0; i < 2000; ++i) {
    const double s = double(rng() % 1000) / 1000.0, t = double(rng() % 1000) / 1000.0;
    const glm::dvec3 d = float_point(a + s * (b - a) + t * (c - a));
    ASSERT_EQ(orientation(a, b, c, d), cgal_orientation(a, b, c, d)) << i;
  }
}

TEST(ExactOrientation, PointsOnOneAxisAlignedPlaneAreCoplanarAndTheSmallestStepOffItIsNot) {
  // A shared coordinate is a zero row (the shortcut before the expansions); a coordinate one
  // float step away (the inputs are floats: down to float's smallest subnormal) is not, and the
  // expansions must still see the sign of that step.
  std::mt19937_64 rng(5);
  const double tiny = std::ldexp(1.0, -149);
  for (int i = 0; i < 3000; ++i) {
    const int axis = int(rng() % 3);
    const double level = i % 3 == 0 ? 0.0 : double(float(std::ldexp(double(rng() % 1000), -5)));
    auto on_plane = [&] {
      glm::dvec3 p = random_float_point(rng, 100.0);
      p[axis] = level;
      return p;
    };
    const glm::dvec3 a = on_plane(), b = on_plane(), c = on_plane();
    glm::dvec3 d = on_plane();
    ASSERT_EQ(orientation(a, b, c, d), 0) << i;
    glm::dvec3 direction = random_float_point(rng, 1.0);
    direction[axis] = 0.0;
    ASSERT_EQ(orientation_towards(a, b, c, direction), 0) << i;
    d[axis] = level == 0.0 ? (i % 2 ? tiny : -tiny)
                           : double(std::nextafter(float(level), i % 2 ? 1e9f : -1e9f));
    ASSERT_EQ(orientation(a, b, c, d), cgal_orientation(a, b, c, d)) << i;
    ASSERT_NE(orientation(a, b, c, d), 0) << i;  // unless a, b, c are collinear: never here
    // The normal is along the axis, so the sign is the normal's times the step's (a + direction
    // would round back to a).
    direction[axis] = i % 2 ? tiny : -tiny;
    glm::dvec3 unit(0.0);
    unit[axis] = 1.0;
    ASSERT_EQ(orientation_towards(a, b, c, direction),
              cgal_orientation(a, b, c, a + unit) * (i % 2 ? 1 : -1))
        << i;
  }
}

TEST(ExactOrientation, TowardsADirectionIsTheOrientationOfThePointPlusTheDirection) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 5000; ++i) {
    // Power-of-two coordinates keep a + u exact, so the two predicates must agree.
    auto dyadic = [&] { return std::ldexp(double(int(rng() % 33) - 16), int(rng() % 8) - 4); };
    const glm::dvec3 a(dyadic(), dyadic(), dyadic()), b(dyadic(), dyadic(), dyadic()),
        c(dyadic(), dyadic(), dyadic()), u(dyadic(), dyadic(), dyadic());
    ASSERT_EQ(orientation_towards(a, b, c, u), cgal_orientation(a, b, c, a + u)) << i;
    ASSERT_EQ(sign(orientation_towards_value(a, b, c, u)), cgal_orientation(a, b, c, a + u));
  }
}

TEST(Expansion, ProductsAndSumsAreExact) {
  // (2^60 + 1)(2^60 - 1) - 2^120 = -1, far below a double's resolution of the product.
  const Expansion<2> x = difference(0x1p60, -1.0), y = difference(0x1p60, 1.0);
  const Expansion<8> xy = product(x, y);
  const Expansion<9> minus_one = sum(xy, expansion_of(-0x1p120));
  ASSERT_EQ(compressed(minus_one).size, 1);
  EXPECT_EQ(compressed(minus_one).component[0], -1.0);
  EXPECT_EQ(sign(sum(xy, expansion_of(-0x1p120 + 0x1p68))), 1);  // 2^68 - 1
}

}  // namespace
}  // namespace shadowcts::geometry
