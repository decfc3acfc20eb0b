// The angular distance is a metric on directions, accurate near 0 and pi, and the arc distances
// agree with a dense sampling of the arc.
#include "reference/metric/angular_distance.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "reference/metric/seeded_random.h"

namespace shadowcts::metric {
namespace {

glm::dvec3 random_direction(std::mt19937_64& rng) {
  while (true) {
    const glm::dvec3 v(2.0 * uniform_unit(rng) - 1.0, 2.0 * uniform_unit(rng) - 1.0,
                       2.0 * uniform_unit(rng) - 1.0);
    const double length = glm::length(v);
    if (length > 0.1 && length <= 1.0) return v / length;
  }
}

// Rotates unit u by `angle` towards a direction orthogonal to it.
glm::dvec3 rotate_away(const glm::dvec3& u, double angle) {
  const glm::dvec3 helper = std::fabs(u.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 orthogonal = glm::normalize(glm::cross(u, helper));
  return std::cos(angle) * u + std::sin(angle) * orthogonal;
}

TEST(AngularDistance, IsAMetricOnRandomDirections) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 x = random_direction(rng), y = random_direction(rng),
                     z = random_direction(rng);
    const double xy = angle_between(x, y), yz = angle_between(y, z), xz = angle_between(x, z);
    ASSERT_GE(xy, 0.0);
    ASSERT_LE(xy, std::numbers::pi);
    ASSERT_EQ(xy, angle_between(y, x));  // bit-identical: |x × y| = |y × x|, x · y = y · x
    ASSERT_LE(xz, xy + yz + 1e-14);
    ASSERT_LT(angle_between(x, x), 1e-15);
  }
}

TEST(AngularDistance, StableNearZeroAndPi) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 u = random_direction(rng);
    for (double angle : {1e-12, 1e-9, 3e-7, 1e-4}) {
      // Near 0 the error stays at the rounding of the inputs (~1e-16), where acos(u . v) would
      // return 0 or noise of ~1e-8.
      EXPECT_NEAR(angle_between(u, rotate_away(u, angle)), angle, 1e-15 + 1e-12 * angle);
      // Absolute accuracy near pi, where acos saturates as well.
      EXPECT_NEAR(angle_between(u, rotate_away(u, std::numbers::pi - angle)),
                  std::numbers::pi - angle, 2e-15);
    }
  }
}

TEST(AngularDistance, ArcDistancesMatchADenseSampling) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 300; ++i) {
    const glm::dvec3 a = random_direction(rng);
    const glm::dvec3 b = rotate_away(a, 0.01 + 3.0 * uniform_unit(rng));
    if (angle_between(a, b) < 0.01) continue;
    const GreatArc arc = make_great_arc(a, b);
    const glm::dvec3 u = random_direction(rng);
    double nearest = std::numbers::pi, farthest = 0.0;
    const int steps = 20000;
    for (int k = 0; k <= steps; ++k) {
      const double s = double(k) / steps;
      // Spherical interpolation between a and b.
      const double theta = 2.0 * arc.half_length;
      const glm::dvec3 point =
          (std::sin((1.0 - s) * theta) * a + std::sin(s * theta) * b) / std::sin(theta);
      nearest = std::min(nearest, angle_between(u, point));
      farthest = std::max(farthest, angle_between(u, point));
    }
    const double spacing = 2.0 * arc.half_length / steps;
    EXPECT_LE(distance_to_arc(u, arc), nearest + 1e-12);
    EXPECT_GE(distance_to_arc(u, arc), nearest - spacing);
    EXPECT_GE(max_distance_to_arc(u, arc), farthest - 1e-12);
    EXPECT_LE(max_distance_to_arc(u, arc), farthest + spacing);
    // Every arc point is within the half length of the midpoint.
    EXPECT_NEAR(angle_between(arc.midpoint, a), arc.half_length, 1e-12);
  }
}

}  // namespace
}  // namespace shadowcts::metric
