// The exact light-assignment oracle: its sets equal a plain loop over every light with the exact
// predicates, its band marks exactly-touching lights, the normal rule, stiff inputs and thread
// independence.
#include "shadowcts/light_assignment_oracle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "light_test_scene.h"
#include "oracles/light_assignment/light_volume_predicates.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"

namespace shadowcts {
namespace {

using testing::ground_quad_case;
using testing::sphere_light;
using testing::spot_light;

std::vector<std::uint32_t> set_of(const LightAssignmentTruth& t, std::size_t s) {
  return {t.lights.begin() + std::ptrdiff_t(t.offsets[s]),
          t.lights.begin() + std::ptrdiff_t(t.offsets[s + 1])};
}

std::vector<std::uint32_t> ambiguous_of(const LightAssignmentTruth& t, std::size_t s) {
  return {t.ambiguous_lights.begin() + std::ptrdiff_t(t.ambiguous_offsets[s]),
          t.ambiguous_lights.begin() + std::ptrdiff_t(t.ambiguous_offsets[s + 1])};
}

// The definition without the index and the band: every light, the exact predicates (whose double
// filters light_volume_predicates_test checks against exact rationals).
std::vector<ExactLightVolume> volumes(const Case& c) {
  std::vector<ExactLightVolume> out;
  for (const RangedLight& l : c.ranged_lights) out.push_back(prepare_light_volume(l));
  return out;
}

std::vector<std::uint32_t> plain_loop(const std::vector<ExactLightVolume>& lights,
                                      const ViewSample& s, bool normal_rule) {
  std::vector<std::uint32_t> out;
  if (s.sample_class != SampleClass::regular) return out;
  const LightQueryPoint p{glm::dvec3(s.position), 0.0, {0, 0, 0}};
  for (std::uint32_t i = 0; i < lights.size(); ++i) {
    const ExactLightVolume& v = lights[i];
    if (light_volume_contains(v, p) && (!normal_rule || light_in_front_of(s.normal, v, p)))
      out.push_back(i);
  }
  return out;
}

TEST(LightAssignmentOracle, EqualsThePlainLoopOverEveryLight) {
  Case c = make_fixture("many_lights.2k");
  c.camera.width = c.camera.height = 40;
  const ViewSamples samples = generate_view_samples(c);
  const std::vector<ExactLightVolume> lights = volumes(c);
  for (const bool normal_rule : {false, true}) {
    const LightAssignmentTruth truth = exact_light_assignment_oracle(c, samples, normal_rule);
    EXPECT_TRUE(truth.exact);
    EXPECT_EQ(truth.normal_rule, normal_rule);
    std::uint64_t total = 0;
    for (std::size_t s = 0; s < samples.samples.size(); ++s) {
      const ViewSample& sample = samples.samples[s];
      if (sample.sample_class != SampleClass::regular) {
        EXPECT_EQ(truth.set_size(s), 0u);
        continue;
      }
      ASSERT_EQ(set_of(truth, s), plain_loop(lights, sample, normal_rule)) << "sample " << s;
      total += truth.set_size(s);
    }
    EXPECT_EQ(truth.exact_minimum(), total);
    EXPECT_GT(total, 0u);
  }
}

TEST(LightAssignmentOracle, LightsTouchingASampleExactlyAreAmbiguous) {
  Case c = ground_quad_case();
  const ViewSamples samples = generate_view_samples(c);
  const std::size_t s = 24 * 48 + 20;
  const ViewSample& sample = samples.samples[s];
  ASSERT_EQ(sample.sample_class, SampleClass::regular);
  ASSERT_EQ(sample.position.y, 0.0f);
  const glm::vec3 above(sample.position.x, 1.0f, sample.position.z);
  c.ranged_lights = {
      sphere_light(above, 1.0f),                  // 0: the sample lies on the sphere
      sphere_light(above, 2.0f),                  // 1: robustly inside
      sphere_light(above, 0.5f),                  // 2: robustly outside
      sphere_light(above, 1e6f),                  // 3: larger than the scene: holds every sample
      spot_light(above, 2.0f, {0, -1, 0}, 0.1f),  // 4: the sample is on its axis
      sphere_light({sample.position.x, -0.5f, sample.position.z}, 1.0f),  // 5: below the ground
  };
  const LightAssignmentTruth plain = exact_light_assignment_oracle(c, samples, false);
  EXPECT_EQ(set_of(plain, s), (std::vector<std::uint32_t>{0, 1, 3, 4, 5}));
  EXPECT_EQ(ambiguous_of(plain, s), (std::vector<std::uint32_t>{0}));
  // With the normal rule the light below the ground drops out.
  const LightAssignmentTruth normals = exact_light_assignment_oracle(c, samples, true);
  EXPECT_EQ(set_of(normals, s), (std::vector<std::uint32_t>{0, 1, 3, 4}));
  std::size_t regular = 0;
  for (std::size_t k = 0; k < samples.samples.size(); ++k) {
    if (samples.samples[k].sample_class != SampleClass::regular) continue;
    ++regular;
    // The huge light holds every sample, far from its boundary.
    EXPECT_TRUE(std::binary_search(plain.lights.begin() + std::ptrdiff_t(plain.offsets[k]),
                                   plain.lights.begin() + std::ptrdiff_t(plain.offsets[k + 1]),
                                   3u));
  }
  EXPECT_EQ(regular, samples.samples.size());
  // A wider band makes more pairs ambiguous, never fewer.
  c.parameters.eps_rel = 0x1p-5;
  const LightAssignmentTruth wide = exact_light_assignment_oracle(c, samples, false);
  EXPECT_GE(wide.ambiguous_lights.size(), plain.ambiguous_lights.size());
  EXPECT_EQ(wide.lights, plain.lights);  // the exact sets do not depend on the band
}

TEST(LightAssignmentOracle, StiffLightPlacements) {
  Case c = ground_quad_case();
  const ViewSamples samples = generate_view_samples(c);
  const glm::vec3 eye = c.camera.position;
  c.ranged_lights = {
      sphere_light(eye + glm::vec3(0, 1, 0), 3.0f),     // behind the camera, out of reach
      sphere_light(eye + glm::vec3(0, 1, 0), 14.0f),    // behind the camera, reaching the ground
      sphere_light(eye - glm::vec3(0, 0.1f, 0), 2.0f),  // on the near plane
      spot_light(eye, 20.0f, {0, -1, 0}, 0.3f),         // at the eye, looking down
  };
  const LightAssignmentTruth truth = exact_light_assignment_oracle(c, samples, false);
  const std::vector<ExactLightVolume> lights = volumes(c);
  for (std::size_t s = 0; s < samples.samples.size(); ++s)
    EXPECT_EQ(set_of(truth, s), plain_loop(lights, samples.samples[s], false)) << s;
  EXPECT_GT(truth.exact_minimum(), 0u);
}

TEST(LightAssignmentOracle, ZeroRangeLightsAreInputErrors) {
  Case c = ground_quad_case();
  c.ranged_lights = {sphere_light({0, 1, 0}, 0.0f)};
  EXPECT_THROW(validate(c), InputError);
  c.ranged_lights = {sphere_light({0, 1, 0}, -1.0f)};
  EXPECT_THROW(validate(c), InputError);
  c.ranged_lights.clear();
  const ViewSamples samples = generate_view_samples(c);
  EXPECT_THROW(exact_light_assignment_oracle(c, samples, false), InputError);
}

TEST(LightAssignmentOracle, SameResultForAnyThreadCount) {
  Case c = make_fixture("depth_gaps.2k");
  c.camera.width = c.camera.height = 64;
  const ViewSamples samples = generate_view_samples(c);
  c.parameters.threads = 1;
  const LightAssignmentTruth one = exact_light_assignment_oracle(c, samples, true);
  c.parameters.threads = 2;
  const LightAssignmentTruth two = exact_light_assignment_oracle(c, samples, true);
  EXPECT_EQ(one.offsets, two.offsets);
  EXPECT_EQ(one.lights, two.lights);
  EXPECT_EQ(one.ambiguous_offsets, two.ambiguous_offsets);
  EXPECT_EQ(one.ambiguous_lights, two.ambiguous_lights);
}

}  // namespace
}  // namespace shadowcts
