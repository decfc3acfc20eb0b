// The exact light-volume predicates: hand cases on exact float boundaries, and the filtered
// evaluation against exact rationals on points within rounding distance of the boundaries.
#include "oracles/light_assignment/light_volume_predicates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace shadowcts {
namespace {

LightQueryPoint at(double x, double y, double z) {
  return {{x, y, z}, 0.0, {0, 0, 0}};
}

RangedLight sphere(glm::vec3 centre, float range) {
  RangedLight l;
  l.centre = centre;
  l.range = range;
  return l;
}

RangedLight spot(glm::vec3 centre, float range, glm::vec3 axis, float half_angle) {
  RangedLight l = sphere(centre, range);
  l.kind = RangedLightKind::spot;
  l.direction = axis;
  l.cone_half_angle = half_angle;
  return l;
}

TEST(LightVolumePredicates, SphereBoundaryIsClosedAndExact) {
  const ExactLightVolume light = prepare_light_volume(sphere({0, 0, 0}, 3.0f));
  EXPECT_TRUE(light_volume_contains(light, at(1, 2, 2)));  // 1 + 4 + 4 = 9: on the sphere
  EXPECT_TRUE(light_volume_contains(light, at(3, 0, 0)));
  EXPECT_FALSE(light_volume_contains(light, at(std::nextafter(3.0f, 4.0f), 0, 0)));
  EXPECT_FALSE(light_volume_contains(light, at(1, 2, std::nextafter(2.0f, 3.0f))));
  EXPECT_TRUE(light_volume_contains(light, at(1, 2, std::nextafter(2.0f, 1.0f))));
  // Moved points are never rounded: (3, 0, 0) + 2^-80 (1, 0, 0) lies outside although its double
  // sum is (3, 0, 0), and (3, 0, 0) - 2^-80 (1, 0, 0) inside.
  EXPECT_FALSE(light_volume_contains(light, LightQueryPoint{{3.0, 0.0, 0.0}, 0x1p-80, {1, 0, 0}}));
  EXPECT_TRUE(light_volume_contains(light, LightQueryPoint{{3.0, 0.0, 0.0}, 0x1p-80, {-1, 0, 0}}));
  EXPECT_FALSE(light_volume_contains(light, LightQueryPoint{{1.0, 2.0, 2.0}, 0x1p-90, {1, 1, 1}}));
}

TEST(LightVolumePredicates, ConeBoundaryAgainstTheTranscendentalCosine) {
  // Points at exactly 45 degrees from the axis: in the cone iff the float half angle exceeds
  // pi / 4; float(pi / 4) is above it, its predecessor below.
  const float above = float(std::numbers::pi / 4);
  ASSERT_GT(double(above), std::numbers::pi / 4);
  const float below = std::nextafter(above, 0.0f);
  ASSERT_LT(double(below), std::numbers::pi / 4);
  const ExactLightVolume wide = prepare_light_volume(spot({0, 0, 0}, 10.0f, {1, 0, 0}, above));
  const ExactLightVolume narrow = prepare_light_volume(spot({0, 0, 0}, 10.0f, {1, 0, 0}, below));
  EXPECT_TRUE(light_volume_contains(wide, at(1, 1, 0)));
  EXPECT_FALSE(light_volume_contains(narrow, at(1, 1, 0)));
  EXPECT_TRUE(light_volume_contains(narrow, at(1, 0, 0)));
  EXPECT_TRUE(light_volume_contains(narrow, at(0, 0, 0)));  // the apex belongs
  EXPECT_FALSE(light_volume_contains(narrow, at(-1, 0, 0)));
  // Beyond pi / 2: a wide cone holds the side but not the back.
  const ExactLightVolume back = prepare_light_volume(spot({0, 0, 0}, 10.0f, {0, 0, 2}, 2.0f));
  EXPECT_TRUE(light_volume_contains(back, at(1, 0, 0)));
  EXPECT_TRUE(light_volume_contains(back, at(1, 0, -0.4)));   // 111.8 degrees < 114.6
  EXPECT_FALSE(light_volume_contains(back, at(1, 0, -0.5)));  // 116.6 degrees > 114.6
  EXPECT_FALSE(light_volume_contains(back, at(0, 0, -1)));
}

TEST(LightVolumePredicates, NormalRuleDropsLightsInTheTangentPlane) {
  const ExactLightVolume light = prepare_light_volume(sphere({1, 0, 0}, 5.0f));
  EXPECT_FALSE(light_in_front_of({0, 1, 0}, light, at(0, 0, 0)));  // n . (c - p) = 0
  EXPECT_TRUE(light_in_front_of({1, 0, 0}, light, at(0, 0, 0)));
  EXPECT_FALSE(light_in_front_of({-1, 0, 0}, light, at(0, 0, 0)));
  EXPECT_TRUE(light_in_front_of({0, 1, 0}, light, LightQueryPoint{{0, 0, 0}, 0x1p-40, {0, -1, 0}}));
}

TEST(LightVolumePredicates, SphereMeetsBoxExactly) {
  const Aabb box{{1, 1, 1}, {2, 2, 2}};
  EXPECT_TRUE(sphere_meets_box({0, 0, 0}, std::sqrt(3.0f) * 1.0000001f, box));
  EXPECT_TRUE(sphere_meets_box({0, 1.5f, 1.5f}, 1.0f, box));  // touches the face
  EXPECT_FALSE(sphere_meets_box({0, 1.5f, 1.5f}, std::nextafter(1.0f, 0.0f), box));
  EXPECT_TRUE(sphere_meets_box({1.5f, 1.5f, 1.5f}, 1e-30f, box));  // inside
  EXPECT_TRUE(sphere_meets_box({0, 0, 1.5f}, std::sqrt(2.0f), box) ==
              exact_only::sphere_meets_box({0, 0, 1.5f}, std::sqrt(2.0f), box));
}

// Points within a few ulps of the boundaries, where the double filter must hand over: the
// filtered answers equal the exact ones everywhere.
TEST(LightVolumePredicates, FilteredEqualsExactNearBoundaries) {
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::uint64_t fallbacks_before = exact_light_predicate_fallbacks();
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const float scale = float(std::ldexp(1.0, int(unit(engine) * 20)));
    const glm::vec3 c(float(unit(engine)) * scale, float(unit(engine)) * scale,
                      float(unit(engine)) * scale);
    const float r = float(std::fabs(unit(engine)) + 0.01) * scale;
    glm::dvec3 axis(unit(engine), unit(engine), unit(engine));
    const RangedLight l =
        trial % 2 == 0 ? sphere(c, r)
                       : spot(c, r, glm::vec3(axis), float(0.1 + 2.9 * std::fabs(unit(engine))));
    const ExactLightVolume v = prepare_light_volume(l);
    // A point on the sphere or on the cone, rounded to floats, nudged by a few ulps.
    glm::dvec3 d(unit(engine), unit(engine), unit(engine));
    d = glm::normalize(d);
    if (trial % 4 == 1) {
      // On the cone surface: rotate the axis towards d by the half angle.
      const glm::dvec3 a = glm::normalize(glm::dvec3(l.direction));
      const glm::dvec3 side = glm::normalize(d - a * glm::dot(d, a));
      d = a * std::cos(double(l.cone_half_angle)) + side * std::sin(double(l.cone_half_angle));
      d *= 0.5;
    }
    glm::vec3 p(glm::dvec3(c) + d * double(r));
    const int nudge = int(unit(engine) * 4);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < std::abs(nudge); ++k)
        p[i] = std::nextafter(p[i], nudge > 0 ? HUGE_VALF : -HUGE_VALF);
    const LightQueryPoint q = at(p.x, p.y, p.z);
    const bool filtered = light_volume_contains(v, q);
    ASSERT_EQ(filtered, exact_only::light_volume_contains(v, q)) << trial;
    (filtered ? inside : outside)++;
    const glm::vec3 n(float(unit(engine)), float(unit(engine)), float(unit(engine)));
    ASSERT_EQ(light_in_front_of(n, v, q), exact_only::light_in_front_of(n, v, q)) << trial;
    const Aabb box{glm::min(p, c), glm::max(p, c + glm::vec3(scale * 1e-7f))};
    const glm::vec3 far(p.x + r, p.y, p.z);
    ASSERT_EQ(sphere_meets_box(far, r, Aabb{p, p}),
              exact_only::sphere_meets_box(far, r, Aabb{p, p}));
    ASSERT_EQ(sphere_meets_box(c, r, box), exact_only::sphere_meets_box(c, r, box));
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
  EXPECT_GT(exact_light_predicate_fallbacks(), fallbacks_before);  // the exact path was taken
}

}  // namespace
}  // namespace shadowcts
