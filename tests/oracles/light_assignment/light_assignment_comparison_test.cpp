// The light-list comparison: a complete and sound assignment passes, and each kind of broken
// list is a Fail with the right example.
#include "oracles/light_assignment/light_assignment_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "light_test_scene.h"

namespace shadowcts {
namespace {

using testing::ground_quad_case;
using testing::sphere_light;

struct ComparisonSetup {
  Case c;
  ViewSamples samples;
  LightAssignmentTruth truth;
  std::size_t touched = 0;  // the sample on light 0's sphere
};

ComparisonSetup make_setup() {
  ComparisonSetup s;
  s.c = ground_quad_case();
  s.samples = generate_view_samples(s.c);
  s.touched = 24 * 48 + 20;
  const glm::vec3 p = s.samples.samples[s.touched].position;
  s.c.ranged_lights = {
      sphere_light({p.x, 1.0f, p.z}, 1.0f),  // 0: touches sample `touched` exactly
      sphere_light({0, 0, 0}, 3.0f),         // 1
      sphere_light({2, 1, 2}, 2.5f),         // 2
      sphere_light({50, 50, 50}, 1.0f),      // 3: far from everything
  };
  s.truth = exact_light_assignment_oracle(s.c, s.samples, false);
  return s;
}

// One list per sample holding exactly its exact set; the box is the sample itself.
LightLists per_sample_lists(const ComparisonSetup& s) {
  LightLists lists;
  for (std::size_t k = 0; k < s.samples.samples.size(); ++k) {
    lists.lights.insert(lists.lights.end(),
                        s.truth.lights.begin() + std::ptrdiff_t(s.truth.offsets[k]),
                        s.truth.lights.begin() + std::ptrdiff_t(s.truth.offsets[k + 1]));
    lists.offsets.push_back(std::uint32_t(lists.lights.size()));
    const glm::vec3 p = s.samples.samples[k].position;
    lists.bounds.push_back({p, p});
    lists.list_of_sample.push_back(std::uint32_t(k));
  }
  return lists;
}

// The list of sample k without light `light`.
void remove_light(LightLists& lists, std::size_t k, std::uint32_t light) {
  for (std::uint32_t e = lists.offsets[k]; e < lists.offsets[k + 1]; ++e)
    if (lists.lights[e] == light) {
      lists.lights.erase(lists.lights.begin() + e);
      for (std::size_t j = k + 1; j < lists.offsets.size(); ++j) --lists.offsets[j];
      return;
    }
  FAIL() << "light " << light << " is not in list " << k;
}

TEST(LightAssignmentComparison, ExactListsPassWithOptimalEfficiency) {
  const ComparisonSetup s = make_setup();
  const LightAssignmentComparison cmp =
      compare_light_lists(per_sample_lists(s), s.c, s.samples, s.truth);
  EXPECT_EQ(cmp.verdict, Verdict::pass) << cmp.reason;
  EXPECT_EQ(cmp.lighting_computations, s.truth.exact_minimum());
  EXPECT_EQ(cmp.exact_minimum, s.truth.exact_minimum());
  EXPECT_DOUBLE_EQ(cmp.lighting_ratio, 1.0);
  EXPECT_EQ(cmp.compared, s.samples.samples.size());
  EXPECT_GE(cmp.ambiguous_members, 1u);
}

TEST(LightAssignmentComparison, OneListForAllIsCompleteSoundAndInefficient) {
  const ComparisonSetup s = make_setup();
  LightLists lists;
  lists.lights = {0, 1, 2};
  lists.offsets = {0, 3};
  Aabb box{{-8, 0, -8}, {8, 0, 8}};
  lists.bounds = {box};
  lists.list_of_sample.assign(s.samples.samples.size(), 0);
  const LightAssignmentComparison cmp = compare_light_lists(lists, s.c, s.samples, s.truth);
  EXPECT_EQ(cmp.verdict, Verdict::pass) << cmp.reason;
  EXPECT_EQ(cmp.lighting_computations, 3 * s.samples.samples.size());
  EXPECT_GT(cmp.lighting_ratio, 1.0);
  // Listing the far light is unsound: its sphere cannot reach the box.
  lists.lights.push_back(3);
  lists.offsets = {0, 4};
  const LightAssignmentComparison unsound = compare_light_lists(lists, s.c, s.samples, s.truth);
  EXPECT_EQ(unsound.verdict, Verdict::fail);
  EXPECT_EQ(unsound.unsound_listings, 1u);
  ASSERT_FALSE(unsound.first_unsound.empty());
  EXPECT_EQ(unsound.first_unsound[0].light, 3u);
  EXPECT_EQ(unsound.first_unsound[0].list, 0u);
}

TEST(LightAssignmentComparison, MissingARobustLightFailsWithSampleLightAndList) {
  const ComparisonSetup s = make_setup();
  // Some sample whose light 1 is robust (not ambiguous).
  std::size_t victim = s.samples.samples.size();
  for (std::size_t k = 0; k < s.samples.samples.size() && victim == s.samples.samples.size(); ++k) {
    bool has = false, ambiguous = false;
    for (auto e = s.truth.offsets[k]; e < s.truth.offsets[k + 1]; ++e)
      has |= s.truth.lights[e] == 1;
    for (auto e = s.truth.ambiguous_offsets[k]; e < s.truth.ambiguous_offsets[k + 1]; ++e)
      ambiguous |= s.truth.ambiguous_lights[e] == 1;
    if (has && !ambiguous) victim = k;
  }
  ASSERT_LT(victim, s.samples.samples.size());
  LightLists lists = per_sample_lists(s);
  remove_light(lists, victim, 1);
  const LightAssignmentComparison cmp = compare_light_lists(lists, s.c, s.samples, s.truth);
  EXPECT_EQ(cmp.verdict, Verdict::fail);
  EXPECT_EQ(cmp.completeness_misses, 1u);
  ASSERT_EQ(cmp.first_misses.size(), 1u);
  EXPECT_EQ(cmp.first_misses[0].sample, victim);
  EXPECT_EQ(cmp.first_misses[0].light, 1u);
  EXPECT_EQ(cmp.first_misses[0].list, victim);
  EXPECT_NE(cmp.reason.find("completeness"), std::string::npos) << cmp.reason;
}

TEST(LightAssignmentComparison, MissingAnAmbiguousLightIsReportedNotFailed) {
  const ComparisonSetup s = make_setup();
  LightLists lists = per_sample_lists(s);
  remove_light(lists, s.touched, 0);
  const LightAssignmentComparison cmp = compare_light_lists(lists, s.c, s.samples, s.truth);
  EXPECT_EQ(cmp.verdict, Verdict::pass) << cmp.reason;
  EXPECT_EQ(cmp.ambiguous_unlisted, 1u);
}

TEST(LightAssignmentComparison, SampleOutsideItsBoundsFails) {
  const ComparisonSetup s = make_setup();
  LightLists lists = per_sample_lists(s);
  lists.bounds[5].max.x = std::nextafter(lists.bounds[5].min.x, -HUGE_VALF);
  lists.bounds[5].min.x = lists.bounds[5].max.x;
  const LightAssignmentComparison cmp = compare_light_lists(lists, s.c, s.samples, s.truth);
  EXPECT_EQ(cmp.verdict, Verdict::fail);
  EXPECT_EQ(cmp.samples_outside_bounds, 1u);
  ASSERT_FALSE(cmp.first_outside.empty());
  EXPECT_EQ(cmp.first_outside[0].sample, 5u);
}

TEST(LightAssignmentComparison, MalformedListsFail) {
  const ComparisonSetup s = make_setup();
  const LightLists good = per_sample_lists(s);
  auto expect_malformed = [&](const LightLists& lists, const char* what) {
    const LightAssignmentComparison cmp = compare_light_lists(lists, s.c, s.samples, s.truth);
    EXPECT_EQ(cmp.verdict, Verdict::fail) << what;
    EXPECT_FALSE(cmp.structure_error.empty()) << what;
  };
  LightLists bad = good;
  bad.offsets.back() += 1;
  expect_malformed(bad, "offsets past the end");
  bad = good;
  bad.bounds.pop_back();
  expect_malformed(bad, "missing bounds");
  bad = good;
  bad.list_of_sample[3] = LightLists::no_list;
  expect_malformed(bad, "regular sample without a list");
  bad = good;
  bad.lights[0] = 99;
  expect_malformed(bad, "light index out of range");
  bad = good;
  std::size_t k = 0;
  while (good.offsets[k + 1] == good.offsets[k]) ++k;  // the first non-empty list
  bad.lights.insert(bad.lights.begin() + bad.offsets[k + 1], bad.lights[bad.offsets[k]]);
  for (std::size_t j = k + 1; j < bad.offsets.size(); ++j) ++bad.offsets[j];
  expect_malformed(bad, "a light twice in one list");
}

TEST(LightAssignmentComparison, NormalRuleVariantsByPaperSuffix) {
  EXPECT_FALSE(light_lists_use_normal_rule("clustered"));
  EXPECT_FALSE(light_lists_use_normal_rule("clustered+eb"));
  EXPECT_TRUE(light_lists_use_normal_rule("clustered+en"));
  EXPECT_TRUE(light_lists_use_normal_rule("clustered+nk3"));
  EXPECT_FALSE(light_lists_use_normal_rule("tiled"));
}

}  // namespace
}  // namespace shadowcts
