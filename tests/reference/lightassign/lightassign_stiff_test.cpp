// Stiff inputs for the light assignment: lights larger than the scene, centres behind the camera,
// on the near plane and at the eye, a near/far ratio of 1e-7, key-bit overflow, samples behind the
// camera, samples outside their pixels, zero-range lights.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lightassign_test_support.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "stiff_scenes.h"

namespace shadowcts {
namespace {

using lightassign_test::small_city;
using testing::counter;
using testing::lightassign;
using testing::run_and_compare;

void expect_every_variant_passes(const Case& c, const ViewSamples& samples) {
  const LightAssignmentTruth plain = exact_light_assignment_oracle(c, samples, false);
  const LightAssignmentTruth normals = exact_light_assignment_oracle(c, samples, true);
  for (const std::string& variant : lightassign().info().variants) {
    SCOPED_TRACE(variant);
    ASSERT_EQ(lightassign().unsupported_reason(c, samples, variant), std::nullopt);
    const auto run = run_and_compare(c, samples, variant, plain, normals);
    EXPECT_EQ(run.comparison.verdict, Verdict::pass) << run.comparison.reason;
  }
}

TEST(LightAssignStiff, LightsLargerThanTheSceneAndAroundTheCamera) {
  const Case c = lightassign_test::city_with_lights_around_the_camera();
  expect_every_variant_passes(c, generate_view_samples(c));
}

TEST(LightAssignStiff, NearFarRatio1e7) {
  const Case c = lightassign_test::city_with_near_far_1e7();
  const ViewSamples samples = generate_view_samples(c);
  expect_every_variant_passes(c, samples);
  // 64 px: 2 x 2 tiles (1 + 1 bits); base 1 + 2 tan(27.5 deg) / 2 = 1.5206, so
  // floor(ln(100 / 1e-5) / ln(1.5206)) + 1 = 39 slices (6 bits).
  const AlgorithmOutput clustered = lightassign().run(c, samples, "clustered");
  EXPECT_EQ(counter(clustered, "key_bits"), 1u + 1u + 6u);
}

TEST(LightAssignStiff, KeyBitOverflowIsNotSupportedWithTheReason) {
  Case c = small_city();
  c.camera.width = c.camera.height = 16384;
  c.camera.vertical_fov_degrees = 1.0f;
  c.camera.near_plane = 1e-5f;
  const ViewSamples no_samples;
  for (const std::string variant : {"clustered", "clustered+eb", "clustered+en", "clustered+nk3"}) {
    const auto why = lightassign().unsupported_reason(c, no_samples, variant);
    ASSERT_TRUE(why.has_value()) << variant;
    EXPECT_NE(why->find("more than the 32-bit key"), std::string::npos) << *why;
  }
  EXPECT_EQ(lightassign().unsupported_reason(c, no_samples, "tiled"), std::nullopt);
  EXPECT_EQ(lightassign().unsupported_reason(c, no_samples, "brute"), std::nullopt);
}

TEST(LightAssignStiff, SamplesBehindTheCameraAreNotSupportedByTilesAndClusters) {
  Case c = small_city();
  ViewSamples samples = generate_view_samples(c);
  std::size_t k = 0;
  while (samples.samples[k].sample_class != SampleClass::regular) ++k;
  ViewSample& s = samples.samples[k];
  s.position = glm::vec3(c.camera.position) * 2.0f - glm::vec3(c.camera.target);
  for (const std::string variant : {"tiled", "clustered", "clustered+nk3"}) {
    const auto why = lightassign().unsupported_reason(c, samples, variant);
    ASSERT_TRUE(why.has_value()) << variant;
    EXPECT_NE(why->find("behind the camera"), std::string::npos) << *why;
  }
  EXPECT_EQ(lightassign().unsupported_reason(c, samples, "brute"), std::nullopt);
}

// A G-buffer from elsewhere (or a fuzzer) may put a sample outside its pixel: here the first
// regular sample takes the place of the last one, across the screen. Tiled would cull its lights
// by its own tile's rectangle and sub-frustum and miss them (found by fuzz_differential), so it
// declines the case; clustered boxes grow to hold their samples and stay complete.
TEST(LightAssignStiff, ASampleOutsideItsPixelIsNotSupportedByTiledOnly) {
  Case c = small_city();
  ViewSamples samples = generate_view_samples(c);
  std::size_t first = 0, last = samples.samples.size() - 1;
  while (samples.samples[first].sample_class != SampleClass::regular) ++first;
  while (samples.samples[last].sample_class != SampleClass::regular) --last;
  samples.samples[first].position = samples.samples[last].position;
  // A small light around it, which only the last pixel's tile sees.
  RangedLight small;
  small.centre = samples.samples[last].position;
  small.range = 1e-3f;
  c.ranged_lights.push_back(small);
  const auto why = lightassign().unsupported_reason(c, samples, "tiled");
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("view sample " + std::to_string(first) + " lies outside"), std::string::npos)
      << *why;
  const LightAssignmentTruth plain = exact_light_assignment_oracle(c, samples, false);
  const LightAssignmentTruth normals = exact_light_assignment_oracle(c, samples, true);
  for (const std::string& variant : lightassign().info().variants) {
    if (variant == "tiled") continue;
    SCOPED_TRACE(variant);
    ASSERT_EQ(lightassign().unsupported_reason(c, samples, variant), std::nullopt);
    const auto run = run_and_compare(c, samples, variant, plain, normals);
    EXPECT_EQ(run.comparison.verdict, Verdict::pass) << run.comparison.reason;
  }
  // What tiled would answer.
  const auto tiled = run_and_compare(c, samples, "tiled", plain, normals);
  EXPECT_GT(tiled.comparison.completeness_misses, 0u);
}

TEST(LightAssignStiff, ZeroRangeLightsAreRejectedByValidation) {
  Case c = small_city();
  c.ranged_lights[3].range = 0.0f;
  EXPECT_THROW(validate(c), InputError);
}

TEST(LightAssignStiff, ReportsItsInfo) {
  const AlgorithmInfo& info = lightassign().info();
  EXPECT_EQ(info.id, "lightassign");
  EXPECT_EQ(info.backend, "reference");
  EXPECT_EQ(info.capabilities.output, OutputKind::light_lists);
  EXPECT_TRUE(info.capabilities.ranged_lights);
  EXPECT_EQ(info.variants, (std::vector<std::string>{"tiled", "clustered", "clustered+eb",
                                                     "clustered+en", "clustered+nk3", "brute"}));
  Case c = small_city();
  c.ranged_lights.clear();
  c.light = ShadowLight{};
  EXPECT_TRUE(lightassign().unsupported_reason(c, ViewSamples{}, "tiled").has_value());
}

}  // namespace
}  // namespace shadowcts
