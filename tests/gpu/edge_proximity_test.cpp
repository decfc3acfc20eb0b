// ray_within_rounding_of_triangle_edge (shadowcts/geometry/edge_proximity.h): it flags every
// segment whose float watertight answer differs from the exact one (checked against the exact
// predicate on segments aimed within rounding of an edge), and not a segment that only passes
// near the extension of an edge's line.
#include "shadowcts/geometry/edge_proximity.h"

#include <gtest/gtest.h>

#include <iostream>

#include <cmath>
#include <random>

#include <glm/vec3.hpp>

#include "oracles/exact_segment_triangle.h"
#include "shadowcts/geometry/segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

bool flagged(const glm::vec3& p, const glm::vec3& light, const Triangle& t) {
  return ray_within_rounding_of_triangle_edge(make_ray_space(segment_to_point_light(p, light)),
                                              t.v0, t.v1, t.v2);
}

TEST(EdgeProximity, AwayFromEdgesAndBesideThemAndOnTheirLinesExtension) {
  const glm::vec3 light(0.0f, 0.0f, 10.0f);
  const Triangle t{{-1.0f, -1.0f, 5.0f}, {1.0f, -1.0f, 5.0f}, {0.0f, 1.0f, 5.0f}, 0};
  // Through the interior, far from every edge.
  EXPECT_FALSE(flagged({0.0f, -0.25f, 0.0f}, light, t));
  // Exactly through the edge from (-1,-1) to (1,-1) at its middle: the segment meets z = 5 at
  // (0, -1).
  EXPECT_TRUE(flagged({0.0f, -2.0f, 0.0f}, light, t));
  // Through the extension of that edge's line, far beyond the triangle: outside for certain.
  const glm::vec3 beyond(8.0f, -2.0f, 0.0f);
  EXPECT_FALSE(flagged(beyond, light, t));
  EXPECT_TRUE(ray_near_triangle_edge(make_ray_space(segment_to_point_light(beyond, light)), t.v0,
                                     t.v1, t.v2))
      << "the looser test of segment_triangle.h flags it";
}

// Segments aimed at a point within 1e-8 to 1e-2 of a random triangle's edge: wherever the float
// test's answer is not the exact predicate's, the segment must be flagged.
TEST(EdgeProximity, FlagsEveryFloatAnswerThatDiffersFromTheExactOne) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int differing = 0, flagged_count = 0;
  const int trials = 20000;
  for (int trial = 0; trial < trials; ++trial) {
    const glm::vec3 light(unit(random), unit(random), 10.0f + unit(random));
    const glm::vec3 centre(2.0f * unit(random), 2.0f * unit(random), 5.0f + unit(random));
    const Triangle t{centre + glm::vec3(unit(random), unit(random), 0.3f * unit(random)),
                     centre + glm::vec3(unit(random), unit(random), 0.3f * unit(random)),
                     centre + glm::vec3(unit(random), unit(random), 0.3f * unit(random)), 0};
    if (is_zero_area(t)) continue;
    // A point on an edge (or at a vertex), moved by 1e-8 .. 1e-2 (log-uniform).
    const glm::vec3 ends[3] = {t.v0, t.v1, t.v2};
    const int edge = trial % 3;
    const double s = trial % 7 == 0 ? 0.0 : fraction(random);
    const glm::dvec3 a(ends[edge]), b(ends[(edge + 1) % 3]);
    const glm::dvec3 jitter(unit(random), unit(random), unit(random));
    const double scale = std::pow(10.0, -8.0 + 6.0 * fraction(random));  // 1e-8 .. 1e-2
    const glm::dvec3 target = a + s * (b - a) + scale * jitter;
    // The sample on z ~ 0, on the line from the light through the target, rounded to float.
    const glm::dvec3 l(light);
    const double k = l.z / (l.z - target.z);
    const glm::vec3 p(l + k * (target - l));
    HardShadowLight exact_light;
    exact_light.position = glm::dvec3(light);
    const ExactShadowPredicate predicate(exact_light, 16.0);
    const bool exact = predicate.blocks(t, MovedPoint{glm::dvec3(p), 0.0, {0, 0, 0}});
    const bool float_answer = ray_hits_triangle(segment_to_point_light(p, light), t.v0, t.v1, t.v2);
    const bool near = flagged(p, light, t);
    flagged_count += near;
    if (float_answer != exact) {
      ++differing;
      EXPECT_TRUE(near) << "trial " << trial << ": float " << float_answer << ", exact " << exact;
    }
  }
  // The aim is close enough to make the float test err sometimes, and the flag stays selective.
  EXPECT_GT(differing, 10);
  EXPECT_LT(flagged_count, trials * 9 / 10);
  std::cout << differing << " float answers differ from the exact ones, " << flagged_count << " of "
            << trials << " segments flagged\n";
}

}  // namespace
}  // namespace shadowcts
