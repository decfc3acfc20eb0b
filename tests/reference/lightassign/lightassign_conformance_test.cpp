// Completeness and soundness of every lightassign variant on the light-assignment fixtures, the
// paper's qualitative result on the depth-discontinuity fixture, and explicit bounds.
#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "lightassign_test_support.h"
#include "shadowcts/fixtures.h"

namespace shadowcts {
namespace {

using testing::counter;
using testing::lightassign;
using testing::run_and_compare;

struct Fixture {
  Case c;
  ViewSamples samples;
  LightAssignmentTruth plain, normals;
};

Fixture prepare(const std::string& name, std::uint32_t side) {
  Fixture f;
  f.c = make_fixture(name);
  f.c.camera.width = f.c.camera.height = side;
  f.samples = generate_view_samples(f.c);
  f.plain = exact_light_assignment_oracle(f.c, f.samples, false);
  f.normals = exact_light_assignment_oracle(f.c, f.samples, true);
  return f;
}

// Modest sizes for CI: every light-assignment generator at two sizes.
const std::vector<std::pair<std::string, std::uint32_t>> light_fixtures = {{"many_lights.2k", 96},
                                                                           {"many_lights.20k", 128},
                                                                           {"depth_gaps.2k", 96},
                                                                           {"depth_gaps.20k", 128}};

TEST(LightAssignConformance, EveryVariantIsCompleteAndSoundOnEveryLightFixture) {
  for (const auto& [name, side] : light_fixtures) {
    const Fixture f = prepare(name, side);
    ASSERT_GT(f.plain.exact_minimum(), 0u) << name << ": the fixture lights nothing";
    for (const std::string& variant : lightassign().info().variants) {
      SCOPED_TRACE(name + " " + variant);
      ASSERT_EQ(lightassign().unsupported_reason(f.c, f.samples, variant), std::nullopt);
      const auto run = run_and_compare(f.c, f.samples, variant, f.plain, f.normals);
      const LightAssignmentComparison& cmp = run.comparison;
      EXPECT_EQ(cmp.verdict, Verdict::pass) << cmp.reason;
      EXPECT_EQ(cmp.completeness_misses, 0u);
      EXPECT_EQ(cmp.unsound_listings, 0u);
      EXPECT_EQ(cmp.samples_outside_bounds, 0u);
      EXPECT_EQ(counter(run.output, "lighting_computations"), cmp.lighting_computations);
      EXPECT_EQ(counter(run.output, "list_lengths_total"), cmp.listed_lights);
      // Complete lists cannot need fewer computations than the exact sets, except by leaving
      // out ambiguous members or lights behind the samples (normal-rule variants).
      if (!light_lists_use_normal_rule(variant)) {
        EXPECT_GE(cmp.lighting_computations + cmp.ambiguous_unlisted, cmp.exact_minimum);
      }
      if (variant == "brute") {
        EXPECT_EQ(cmp.lighting_computations, cmp.exact_minimum);
      }
      std::printf("%-16s %-14s misses %llu unsound %llu lighting %llu min %llu ratio %.2f\n",
                  name.c_str(), variant.c_str(), (unsigned long long)cmp.completeness_misses,
                  (unsigned long long)cmp.unsound_listings,
                  (unsigned long long)cmp.lighting_computations,
                  (unsigned long long)cmp.exact_minimum, cmp.lighting_ratio);
    }
  }
}

TEST(LightAssignConformance, ResultsDoNotDependOnTheThreadCount) {
  Fixture f = prepare("depth_gaps.2k", 64);
  for (const std::string& variant : lightassign().info().variants) {
    SCOPED_TRACE(variant);
    f.c.parameters.threads = 1;
    const AlgorithmOutput one = lightassign().run(f.c, f.samples, variant);
    f.c.parameters.threads = 2;
    const AlgorithmOutput two = lightassign().run(f.c, f.samples, variant);
    EXPECT_EQ(one.light_lists.offsets, two.light_lists.offsets);
    EXPECT_EQ(one.light_lists.lights, two.light_lists.lights);
    EXPECT_EQ(one.light_lists.list_of_sample, two.light_lists.list_of_sample);
    EXPECT_EQ(one.counters, two.counters);
  }
}

TEST(LightAssignConformance, ExplicitBoundsAreTheBoxesOfTheirSamples) {
  const Fixture f = prepare("depth_gaps.2k", 96);
  const AlgorithmOutput eb = lightassign().run(f.c, f.samples, "clustered+eb");
  const AlgorithmOutput implicit = lightassign().run(f.c, f.samples, "clustered");
  const LightLists& lists = eb.light_lists;
  // The same clusters either way; explicit boxes are exactly the min/max of their samples and
  // lie inside the implicit ones.
  ASSERT_EQ(lists.list_of_sample, implicit.light_lists.list_of_sample);
  std::vector<Aabb> expected(lists.bounds.size());
  std::vector<bool> seen(lists.bounds.size(), false);
  for (const ViewSample& s : f.samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const std::uint32_t k =
        lists.list_of_sample[std::size_t(s.pixel_y) * f.samples.width + s.pixel_x];
    if (!seen[k]) expected[k].min = expected[k].max = s.position;
    seen[k] = true;
    expected[k].min = glm::min(expected[k].min, s.position);
    expected[k].max = glm::max(expected[k].max, s.position);
  }
  for (std::size_t k = 0; k < lists.bounds.size(); ++k) {
    ASSERT_TRUE(seen[k]) << "cluster " << k << " has no sample";
    EXPECT_EQ(lists.bounds[k].min, expected[k].min) << k;
    EXPECT_EQ(lists.bounds[k].max, expected[k].max) << k;
    const Aabb& outer = implicit.light_lists.bounds[k];
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(outer.min[i], lists.bounds[k].min[i]);
      EXPECT_GE(outer.max[i], lists.bounds[k].max[i]);
    }
  }
  // Tighter boxes never list more lights.
  EXPECT_LE(counter(eb, "list_lengths_total"), counter(implicit, "list_lengths_total"));
}

// Paper II's qualitative result (Figure 10a, Section 5.1): with depth discontinuities tiles
// include the empty space between near and far samples, clusters do not.
TEST(LightAssignConformance, ClusteredNeedsFarFewerLightingComputationsThanTiledAcrossDepthGaps) {
  const Fixture f = prepare("depth_gaps.20k", 256);
  const auto tiled = run_and_compare(f.c, f.samples, "tiled", f.plain, f.normals);
  const auto clustered = run_and_compare(f.c, f.samples, "clustered", f.plain, f.normals);
  const auto brute = run_and_compare(f.c, f.samples, "brute", f.plain, f.normals);
  std::printf("depth_gaps.20k 256^2: tiled %llu, clustered %llu, exact minimum %llu\n",
              (unsigned long long)tiled.comparison.lighting_computations,
              (unsigned long long)clustered.comparison.lighting_computations,
              (unsigned long long)brute.comparison.lighting_computations);
  EXPECT_LT(3 * clustered.comparison.lighting_computations, tiled.comparison.lighting_computations);
  EXPECT_LE(brute.comparison.lighting_computations, clustered.comparison.lighting_computations);
}

}  // namespace
}  // namespace shadowcts
