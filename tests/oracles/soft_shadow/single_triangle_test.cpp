// The closed-form single-triangle oracle against known areas, and the exact oracle against it on
// single triangles: containing the disk, crossing the fragment plane, touching the disk boundary,
// slivers, random ones, and the stiff angular radii.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "shadowcts/errors.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

using testing::sun_disk;

// The light straight up, so light space is world space up to the axes' naming: a caster at height
// h over the sample p projects by (x, z) / (h tan a).
const glm::vec3 up{0.0f, 1.0f, 0.0f};

// Fraction of the unit disk on the far side of a chord at distance h from the centre.
double beyond_chord(double h) {
  return (std::acos(h) - h * std::sqrt(1.0 - h * h)) / std::numbers::pi;
}

double exact_single(const ShadowLight& light, const glm::vec3& p, const Triangle& t) {
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle(t.v0, t.v1, t.v2);
  h.add_ground_sample(p);
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  EXPECT_TRUE(truth.exact);
  return truth.visible_fraction[0];
}

void expect_agreement(const ShadowLight& light, const glm::vec3& p, const Triangle& t) {
  const double closed = single_triangle_visible_fraction(light, glm::dvec3(p), t);
  EXPECT_NEAR(exact_single(light, p, t), closed, 1e-9)
      << "triangle (" << t.v0.x << "," << t.v0.y << "," << t.v0.z << ") (" << t.v1.x << ","
      << t.v1.y << "," << t.v1.z << ") (" << t.v2.x << "," << t.v2.y << "," << t.v2.z << ")";
}

TEST(ClosedForm, HalfPlaneThroughTheCentreHidesHalf) {
  const ShadowLight light = sun_disk(up, 2.0);
  const Triangle t{{0, 1, -100}, {0, 1, 100}, {100, 1, 0}, testing::blocker_mesh};
  EXPECT_NEAR(single_triangle_visible_fraction(light, {0, 0, 0}, t), 0.5, 1e-12);
  EXPECT_NEAR(exact_single(light, {0, 0, 0}, t), 0.5, 1e-12);
}

TEST(ClosedForm, ChordAtKnownDistance) {
  const ShadowLight light = sun_disk(up, 2.0);
  const double tan_a = std::tan(double(light.angular_radius));
  for (double h : {0.1, 0.5, 0.9, 0.999}) {
    // An edge along z at x = h tan(a) (height 1): the caster hides the part of the disk beyond it.
    const auto x = float(h * tan_a);
    const Triangle t{{x, 1, -100}, {x, 1, 100}, {100, 1, 0}, testing::blocker_mesh};
    const double expected = 1.0 - beyond_chord(double(x) / tan_a);
    EXPECT_NEAR(single_triangle_visible_fraction(light, {0, 0, 0}, t), expected, 1e-12) << h;
    EXPECT_NEAR(exact_single(light, {0, 0, 0}, t), expected, 1e-12) << h;
  }
}

TEST(ClosedForm, TriangleContainingTheDiskHidesAll) {
  const ShadowLight light = sun_disk(up, 2.0);
  const Triangle t{{-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, testing::blocker_mesh};
  EXPECT_EQ(single_triangle_visible_fraction(light, {0, 0, 0}, t), 0.0);
  EXPECT_EQ(exact_single(light, {0, 0, 0}, t), 0.0);
}

TEST(ClosedForm, TriangleAwayFromTheDiskHidesNothing) {
  const ShadowLight light = sun_disk(up, 2.0);
  const Triangle t{{3, 1, 0}, {4, 1, 0}, {3, 1, 1}, testing::blocker_mesh};
  EXPECT_EQ(single_triangle_visible_fraction(light, {0, 0, 0}, t), 1.0);
  EXPECT_EQ(exact_single(light, {0, 0, 0}, t), 1.0);
  // Behind the sample (below the fragment plane towards the light): nothing either.
  const Triangle below{{-1, -1, -1}, {1, -1, -1}, {0, -1, 1}, testing::blocker_mesh};
  EXPECT_EQ(exact_single(light, {0, 0, 0}, below), 1.0);
}

TEST(ExactVsClosedForm, TriangleContainingTheDiskCentre) {
  const ShadowLight light = sun_disk({0.3f, 1.0f, 0.2f}, 5.0);
  expect_agreement(light, {0.25f, 0, 0.125f},
                   {{0.2f, 2, 0.1f}, {0.4f, 2.1f, 0.2f}, {0.3f, 2, 0.3f}, 1});
}

TEST(ExactVsClosedForm, TriangleCrossingTheFragmentPlane) {
  // One vertex below the sample's plane perpendicular to d: the projection is unbounded and is
  // clipped homogeneously.
  const ShadowLight light = sun_disk(up, 3.0);
  for (float below : {-0.5f, -2.0f, -1e-3f}) {
    expect_agreement(light, {0, 0.5f, 0},
                     {{0.02f, 1.5f, -0.01f}, {0.03f, 2, 0.04f}, {0.01f, below, 0.02f}, 1});
    expect_agreement(light, {0, 0.5f, 0},
                     {{-0.5f, 1, 0.05f}, {0.5f, 1, 0.05f}, {0, below, 0.0f}, 1});
  }
}

TEST(ExactVsClosedForm, TriangleTouchingTheDiskBoundary) {
  // A vertex exactly on the circle (dyadic: tan(a) chosen as a float for which the vertex is
  // representable is impossible, so approach it from both sides within one float step).
  const ShadowLight light = sun_disk(up, 2.0);
  const double tan_a = std::tan(double(light.angular_radius));
  const auto r = float(tan_a);
  for (float x : {std::nextafter(r, 0.0f), r, std::nextafter(r, 1.0f)}) {
    expect_agreement(light, {0, 0, 0}, {{x, 1, 0}, {1, 1, -0.5f}, {1, 1, 0.5f}, 1});
    // An edge tangent to the circle.
    expect_agreement(light, {0, 0, 0}, {{x, 1, -1}, {x, 1, 1}, {2, 1, 0}, 1});
  }
}

TEST(ExactVsClosedForm, SliverTriangles) {
  const ShadowLight light = sun_disk(up, 2.0);
  // Long and 1e-4 (then 1e-7) of the disk wide, across the centre; and a needle ending inside.
  for (float width : {1e-4f, 1e-7f}) {
    const float w = width * 0.035f;
    expect_agreement(light, {0, 0, 0}, {{-1, 1, -w}, {1, 1, 0}, {-1, 1, w}, 1});
    expect_agreement(light, {0, 0, 0}, {{-1, 1, -w}, {0.01f, 1, 0.002f}, {-1, 1, w}, 1});
  }
}

TEST(ExactVsClosedForm, RandomTrianglesNearTheCone) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (double degrees : {0.27, 2.0, 10.0, 45.0}) {
    const ShadowLight light = sun_disk({0.4f, 1.0f, -0.3f}, degrees);
    const glm::vec3 d = glm::normalize(light.direction);
    for (int i = 0; i < 60; ++i) {
      const float height = 0.5f + 2.0f * (unit(random) + 1.0f);
      const float spread = height * float(std::tan(degrees * std::numbers::pi / 180.0)) * 1.5f;
      const glm::vec3 p{unit(random), 0.0f, unit(random)};
      const auto corner = [&] {
        return p + height * d + spread * glm::vec3(unit(random), unit(random), unit(random));
      };
      expect_agreement(light, p, {corner(), corner(), corner(), 1});
    }
  }
}

TEST(StiffInputs, TinyAngularRadius) {
  // 1e-6 rad: the disk is 1e-6 wide at distance 1; the projected coordinates are large but exact
  // arithmetic does not care.
  ShadowLight light = sun_disk(up, 1.0);
  light.angular_radius = 1e-6f;
  const double tan_a = std::tan(double(light.angular_radius));
  const auto x = float(0.5 * tan_a);
  const Triangle t{{x, 1, -1}, {x, 1, 1}, {1, 1, 0}, 1};
  const double expected = 1.0 - beyond_chord(double(x) / tan_a);
  EXPECT_NEAR(single_triangle_visible_fraction(light, {0, 0, 0}, t), expected, 1e-9);
  EXPECT_NEAR(exact_single(light, {0, 0, 0}, t), expected, 1e-9);
}

TEST(StiffInputs, ZeroAngularRadiusIsAnInputError) {
  ShadowLight light = sun_disk(up, 1.0);
  light.angular_radius = 0.0f;
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_ground_sample({0, 0, 0});
  EXPECT_THROW(validate(h.c), InputError);
  EXPECT_THROW(exact_soft_shadow_oracle(h.c, h.samples), InputError);
  EXPECT_THROW(sampled_soft_shadow_oracle(h.c, h.samples, 16), InputError);
  EXPECT_THROW(single_triangle_visible_fraction(light, {0, 0, 0}, h.c.triangles[0]), InputError);
}

TEST(StiffInputs, OtherLightsAreAnInputError) {
  testing::HandBuiltCase h = testing::make_hand_built_case(testing::directional_light(up));
  h.add_ground_sample({0, 0, 0});
  EXPECT_THROW(exact_soft_shadow_oracle(h.c, h.samples), InputError);
  EXPECT_THROW(sampled_soft_shadow_oracle(h.c, h.samples, 16), InputError);
}

}  // namespace
}  // namespace shadowcts
