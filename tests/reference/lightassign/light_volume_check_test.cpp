// The brute-force light loop's own volume test against the oracle's exact predicate: it never
// drops a light the oracle keeps, keeps one the oracle drops only where it says it is undecided,
// and decides nearly every random sample, spots wider than a hemisphere and the apex included.
#include "reference/lightassign/light_volume_check.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "oracles/light_assignment/light_volume_predicates.h"

namespace shadowcts {
namespace {

TEST(LightVolumeCheck, AgreesWithTheExactOracleWhereverItDecides) {
  std::mt19937_64 engine(20261202);
  std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f), range(0.1f, 5.0f),
      angle(0.01f, 3.1f);
  std::uint64_t decided = 0, undecided = 0, inside = 0;
  for (int l = 0; l < 200; ++l) {
    RangedLight light;
    light.kind = l % 4 == 0 ? RangedLightKind::sphere : RangedLightKind::spot;
    light.centre = {coordinate(engine), coordinate(engine), coordinate(engine)};
    light.range = range(engine);
    const glm::vec3 axis{coordinate(engine), coordinate(engine), coordinate(engine)};
    light.direction = axis / std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    light.cone_half_angle = angle(engine);
    const LightVolumeCheck check(light);
    const ExactLightVolume exact = prepare_light_volume(light);
    for (int s = 0; s < 500; ++s) {
      // Half of the points on the light's own axis lines or at its centre: the boundary cases.
      glm::vec3 x{coordinate(engine), coordinate(engine), coordinate(engine)};
      if (s == 0) x = light.centre;
      if (s % 2 == 1) x = light.centre + (coordinate(engine) * 0.5f) * light.direction;
      const bool truth = light_volume_contains(exact, {glm::dvec3(x), 0.0, {0, 0, 0}});
      const int answer = check.contains(x);
      if (answer < 0) {
        ++undecided;
        continue;
      }
      ++decided;
      inside += answer;
      ASSERT_EQ(answer == 1, truth) << "light " << l << ", sample " << s;
    }
  }
  EXPECT_GT(inside, 1000u);
  EXPECT_LE(undecided, decided / 1000);
}

TEST(LightVolumeCheck, KeepsTheApexAndDecidesTheRangeExactly) {
  RangedLight spot;
  spot.kind = RangedLightKind::spot;
  spot.centre = {1.0f, 2.0f, 3.0f};
  spot.range = 2.0f;
  spot.direction = {0.0f, 0.0f, -1.0f};
  spot.cone_half_angle = 0.5f;
  const LightVolumeCheck check(spot);
  EXPECT_EQ(check.contains(spot.centre), 1);
  EXPECT_EQ(check.contains({1.0f, 2.0f, 1.0f}), 1);                        // exactly at the range
  EXPECT_EQ(check.contains({1.0f, 2.0f, std::nextafter(1.0f, 0.0f)}), 0);  // one ulp beyond
  EXPECT_EQ(check.contains({1.0f, 2.0f, 4.0f}), 0);                        // behind the spot
}

}  // namespace
}  // namespace shadowcts
