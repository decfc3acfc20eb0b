// The shadow-map baseline: its rasterizer's fill rule, its cube faces, and its error against the
// exact oracle, which must shrink as the maps get finer.
#include "reference/shadowmap/shadowmap_algorithm.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "reference/shadowmap/cube_map.h"
#include "reference/shadowmap/rasterizer.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

using namespace shadowmap;

TEST(ShadowMap, DescribesItself) {
  const auto algorithm = make_shadowmap();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "shadowmap");
  EXPECT_EQ(info.backend, "reference");
  EXPECT_EQ(info.variants, (std::vector<std::string>{"1k", "2k", "4k", "8k", "2k+nobias"}));
  EXPECT_TRUE(info.capabilities.approximate);
  EXPECT_TRUE(info.capabilities.point_light);
  EXPECT_TRUE(info.capabilities.directional_light);
}

// An orthographic 8x8 view of the square [-4, 4]^2 (z = 1), where texel (i, j) has its centre at
// world (i - 3.5, j - 3.5): the square's diagonal runs exactly through the centres (i, i).
LightView square_view() {
  LightView view;
  view.perspective = false;
  view.origin = {0.0, 0.0, 0.0};
  view.half_extent = 4.0;
  view.resolution = 8;
  return view;
}

std::vector<bool> coverage(const std::vector<Triangle>& triangles) {
  DepthMap map;
  map.reset_full(square_view().resolution);
  rasterize_depth(square_view(), triangles, map);
  std::vector<bool> covered;
  for (float d : map.depth) covered.push_back(d < 1e30f);
  return covered;
}

TEST(ShadowMapRasterizer, TopLeftRuleCoversSharedEdgeCentresExactlyOnce) {
  const glm::vec3 a{-3, -3, 1}, b{3, -3, 1}, c{3, 3, 1}, d{-3, 3, 1};
  for (const bool reversed : {false, true}) {  // both windings
    const Triangle lower = reversed ? Triangle{a, c, b, 0} : Triangle{a, b, c, 0};
    const Triangle upper = reversed ? Triangle{a, d, c, 0} : Triangle{a, c, d, 0};
    const std::vector<bool> one = coverage({lower}), two = coverage({upper});
    int both = 0, either = 0, diagonal = 0;
    for (std::size_t i = 0; i < one.size(); ++i) {
      both += one[i] && two[i];
      either += one[i] || two[i];
      const std::size_t row = i / 8, column = i % 8;
      diagonal += row == column && (one[i] || two[i]);
    }
    EXPECT_EQ(both, 0);
    EXPECT_EQ(diagonal, 6);  // centres (-2.5 ... 2.5) on the shared edge, each covered once
    EXPECT_EQ(either, 36);   // the 6 x 6 centres inside [-3, 3]^2
  }
}

TEST(ShadowMapRasterizer, KeepsTheNearestDepthAndCountsWrites) {
  const Triangle far{{-3, -3, 5}, {3, -3, 5}, {0, 3, 5}, 0};
  const Triangle near{{-3, -3, 2}, {3, -3, 2}, {0, 3, 2}, 0};
  DepthMap map;
  map.reset_full(square_view().resolution);
  const RasterCounters counters = rasterize_depth(square_view(), {far, near}, map);
  EXPECT_EQ(counters.triangles_rasterized, 2u);
  std::uint64_t covered = 0;
  for (float depth : map.depth)
    if (depth < 1e30f) {
      EXPECT_EQ(depth, 2.0f);
      ++covered;
    }
  EXPECT_EQ(counters.texels_written, 2 * covered);  // far first, then near overwrites
}

// A map that keeps some texels holds there what the full map holds, and counts the writes there.
TEST(ShadowMapRasterizer, KeptTexelsHoldTheFullMapsDepths) {
  LightView view;
  view.perspective = true;
  view.near = 0.05;
  view.resolution = 64;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> lateral(-3.0f, 3.0f), depth(0.5f, 4.0f);
  std::vector<Triangle> casters;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 centre(lateral(rng), lateral(rng), depth(rng));
    casters.push_back({centre + glm::vec3(lateral(rng), lateral(rng), lateral(rng)) * 0.3f,
                       centre + glm::vec3(lateral(rng), lateral(rng), lateral(rng)) * 0.3f,
                       centre + glm::vec3(lateral(rng), lateral(rng), lateral(rng)) * 0.3f, 0});
  }
  DepthMap full;
  full.reset_full(view.resolution);
  const RasterCounters all = rasterize_depth(view, casters, full);
  std::vector<std::uint64_t> texels;
  std::uniform_int_distribution<std::uint64_t> texel(0, 64 * 64 - 1);
  for (int i = 0; i < 500; ++i) texels.push_back(texel(rng));
  std::sort(texels.begin(), texels.end());
  texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
  DepthMap kept;
  kept.reset(view.resolution, texels);
  const RasterCounters some = rasterize_depth(view, casters, kept);
  EXPECT_EQ(some.triangles_rasterized, all.triangles_rasterized);
  int covered = 0;
  for (const std::uint64_t t : texels) {
    const auto column = std::uint32_t(t % 64), row = std::uint32_t(t / 64);
    EXPECT_EQ(kept.at(column, row), full.at(column, row)) << "texel " << column << ", " << row;
    covered += full.at(column, row) < 1e30f;
  }
  EXPECT_GT(covered, 100);
  EXPECT_GT(some.texels_written, 0u);
  EXPECT_LT(some.texels_written, all.texels_written);
}

TEST(ShadowMapCube, EveryDirectionHasOneFaceThatSeesIt) {
  for (const glm::dvec3& d : {glm::dvec3(1, 0.5, -0.25), glm::dvec3(-0.5, -2, 1),
                              glm::dvec3(0.25, 0.5, 3), glm::dvec3(1, 1, 1)}) {
    const LightView face = cube_face_view(glm::dvec3(0.0), cube_face_of(d), 16, 0.01);
    const glm::dvec3 v = face.to_view(d);
    EXPECT_GT(v.z, 0.0);
    EXPECT_LE(std::fabs(v.x), v.z);
    EXPECT_LE(std::fabs(v.y), v.z);
  }
}

// The hard-shadow view of a fixture: a sun disk is seen as its centre direction, as the runner
// does.
Case hard_view(Case c) {
  if (c.light && c.light->kind == ShadowLightKind::sun_disk) {
    c.light->kind = ShadowLightKind::directional;
    c.light->angular_radius = 0.0f;
  }
  return c;
}

TEST(ShadowMapAgainstExactOracle, ErrorShrinksWithResolutionOnTheDefaultFixtures) {
  const auto algorithm = make_shadowmap();
  std::map<std::string, double> total_rate;
  std::uint64_t false_shadows_biased = 0, false_shadows_unbiased = 0;
  int fixtures = 0;
  for (const std::string& name : default_fixtures()) {
    const Case c = hard_view(make_fixture(name));
    if (!c.light) continue;  // ranged lights only
    const ViewSamples samples = generate_view_samples(c);
    ASSERT_FALSE(algorithm->unsupported_reason(c, samples, "1k")) << name;
    const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
    double rate[4] = {0, 0, 0, 0};
    const char* variants[4] = {"1k", "2k", "4k", "8k"};
    for (int v = 0; v < 4; ++v) {
      const AlgorithmOutput output = algorithm->run(c, samples, variants[v]);
      const HardShadowComparison h = compare_hard_shadows(output.shadowed, truth);
      ASSERT_GT(h.robust, 0u) << name;
      rate[v] = double(h.leaks + h.false_shadows) / double(h.robust);
      total_rate[variants[v]] += rate[v];
      if (v == 1) false_shadows_biased += h.false_shadows;
    }
    const HardShadowComparison unbiased =
        compare_hard_shadows(algorithm->run(c, samples, "2k+nobias").shadowed, truth);
    false_shadows_unbiased += unbiased.false_shadows;
    // Per fixture: the finest map is at least as good as the coarsest, and close to right.
    EXPECT_LE(rate[3], rate[0]) << name;
    EXPECT_LT(rate[3], 0.01) << name;
    ++fixtures;
  }
  ASSERT_GE(fixtures, 5);
  // Over the whole default set the error decreases strictly with every doubling.
  EXPECT_GT(total_rate["1k"], total_rate["2k"]);
  EXPECT_GT(total_rate["2k"], total_rate["4k"]);
  EXPECT_GT(total_rate["4k"], total_rate["8k"]);
  // Without bias the receivers shadow themselves (acne).
  EXPECT_GT(false_shadows_unbiased, 10 * (false_shadows_biased + 1));
}

TEST(ShadowMap, SameResultForAnyThreadCount) {
  for (const char* name : {"ground_blockers.10k", "closed_shapes.10k"}) {
    Case c = make_fixture(name);
    const ViewSamples samples = generate_view_samples(c);
    const auto algorithm = make_shadowmap();
    c.parameters.threads = 2;
    const AlgorithmOutput many = algorithm->run(c, samples, "2k");
    c.parameters.threads = 1;
    const AlgorithmOutput one = algorithm->run(c, samples, "2k");
    EXPECT_EQ(one.shadowed, many.shadowed) << name;
    EXPECT_EQ(one.counters, many.counters) << name;
    ASSERT_EQ(one.counters.size(), 3u);
    EXPECT_EQ(one.counters[0].first, "texels_written");
    EXPECT_EQ(one.counters[1].first, "triangles_rasterized");
    EXPECT_GT(one.counters[0].second, 0u);
    EXPECT_GT(one.counters[1].second, 0u);
  }
}

TEST(ShadowMap, RejectsUnknownVariants) {
  const Case c = make_fixture("closed_shapes.10k");
  const ViewSamples samples = generate_view_samples(c);
  EXPECT_THROW(make_shadowmap()->run(c, samples, "3k"), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
