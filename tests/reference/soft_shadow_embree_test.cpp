// The Embree soft-shadow baseline: its stratified disk points, exact answers where no ray can be
// blocked or every ray is, the receiver half-space rule per ray, the error against the exact disk
// oracle falling with N on the default soft fixture within the declared budgets, determinism.
#include "reference/embree/soft_shadow_embree.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "oracles/soft_shadow/soft_shadow_comparison.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

using testing::sun_disk;

const std::vector<std::string> variant_names = {"rays16", "rays64", "rays256"};

TEST(EmbreeSoftShadow, DescribesItselfAndItsBudgets) {
  const auto algorithm = make_embree_soft_shadow();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "embree_soft");
  EXPECT_EQ(info.backend, "embree");
  EXPECT_EQ(info.variants, variant_names);
  EXPECT_EQ(info.capabilities.output, OutputKind::soft_shadow);
  EXPECT_TRUE(info.capabilities.sun_disk);
  EXPECT_FALSE(info.capabilities.point_light);
  EXPECT_THROW(embree_soft_rays("rays17"), std::invalid_argument);
  double previous_per_sample = 1.0, previous_mean = 1.0;
  for (const std::string& variant : variant_names) {
    const SoftErrorBudget budget = algorithm->soft_error_budget(variant);
    const double n = embree_soft_rays(variant);
    // Hoeffding at failure probability 1e-9; twice the worst-case standard deviation.
    EXPECT_DOUBLE_EQ(budget.per_sample, std::sqrt(std::log(2e9) / (2.0 * n))) << variant;
    EXPECT_DOUBLE_EQ(budget.mean, 1.0 / std::sqrt(n)) << variant;
    EXPECT_LT(budget.per_sample, previous_per_sample);
    EXPECT_LT(budget.mean, previous_mean);
    previous_per_sample = budget.per_sample;
    previous_mean = budget.mean;
  }
}

TEST(EmbreeSoftShadow, DiskPointsAreStratifiedEqualAreaAndSeeded) {
  for (std::uint32_t rays : {16u, 64u, 256u}) {
    const auto k = std::uint32_t(std::lround(std::sqrt(double(rays))));
    std::uint32_t inner = 0;
    glm::dvec2 mean(0.0);
    for (std::uint32_t s = 0; s < rays; ++s) {
      const glm::dvec2 q = embree_soft_disk_point(7, 1234, rays, s);
      ASSERT_LE(glm::length(q), 1.0) << rays << " " << s;
      EXPECT_EQ(q, embree_soft_disk_point(7, 1234, rays, s));
      EXPECT_NE(q, embree_soft_disk_point(8, 1234, rays, s));
      EXPECT_NE(q, embree_soft_disk_point(7, 1235, rays, s));
      inner += glm::dot(q, q) < 0.5 ? 1 : 0;
      mean += q / double(rays);
    }
    // Equal-area strata: half the disk's area lies within radius 1/sqrt(2); only the strata the
    // circle crosses (about 2 k of them) can fall on either side.
    EXPECT_NEAR(double(inner), rays / 2.0, 2.0 * k) << rays;
    EXPECT_LT(glm::length(mean), 2.0 / k) << rays;
  }
}

TEST(EmbreeSoftShadow, NoCasterGivesExactlyOneAndACoveringCasterExactlyZero) {
  testing::HandBuiltCase h = testing::make_hand_built_case(sun_disk({0.3f, 1.0f, -0.2f}, 4.0));
  // Things that cannot shadow: a triangle of a non-caster mesh and a zero-area caster above.
  h.add_triangle({-4, 2, -4}, {4, 2, -4}, {0, 2, 4}, testing::ground_mesh);
  h.add_triangle({-1, 1, 0}, {1, 1, 0}, {3, 1, 0});
  for (int i = 0; i < 16; ++i) h.add_ground_sample({-1.5f + 0.2f * float(i), 0.0f, 0.25f});
  for (const std::string& variant : variant_names) {
    const AlgorithmOutput output = make_embree_soft_shadow()->run(h.c, h.samples, variant);
    ASSERT_EQ(output.visible_fraction.size(), h.samples.samples.size());
    for (float f : output.visible_fraction) EXPECT_EQ(f, 1.0f) << variant;
    ASSERT_EQ(output.counters.size(), 2u);
    EXPECT_EQ(output.counters[0].first, "rays");
    EXPECT_EQ(output.counters[0].second, 16u * embree_soft_rays(variant));
    EXPECT_EQ(output.counters[1].first, "occluded_rays");
    EXPECT_EQ(output.counters[1].second, 0u);
  }
  // A caster over the whole ground blocks every ray of every sample.
  h.add_triangle({-40, 1, -40}, {40, 1, -40}, {0, 1, 40});
  for (const std::string& variant : variant_names) {
    const AlgorithmOutput output = make_embree_soft_shadow()->run(h.c, h.samples, variant);
    for (float f : output.visible_fraction) EXPECT_EQ(f, 0.0f) << variant;
    EXPECT_EQ(output.counters[1].second, 16u * embree_soft_rays(variant));
  }
}

TEST(EmbreeSoftShadow, CoplanarNeighbourDoesNotShadowButACreaseDoes) {
  // A low sun towards +x over a caster floor of two triangles sharing the edge x = 0.
  testing::HandBuiltCase h = testing::make_hand_built_case(
      sun_disk(glm::vec3(glm::normalize(glm::dvec3(1.0, 0.05, 0.0))), 0.5));
  const std::uint32_t west =
      h.add_triangle({0, 0, -4}, {0, 0, 4}, {-8, 0, 4}, testing::caster_ground_mesh);
  const std::uint32_t east =
      h.add_triangle({0, 0, -4}, {0, 0, 4}, {8, 0, 4}, testing::caster_ground_mesh);
  // Just below the floor and just west of the shared edge: every ray crosses y = 0 over the east
  // triangle (at x ~ 2^-24 / 0.05 - 2^-22 > 0), below nothing on the light's side of the plane.
  const std::size_t beside_edge = h.add_sample({-0x1p-22f, -0x1p-24f, 0.0f}, west);
  const std::size_t before_wall = h.add_sample({0.5f, 0.0f, 0.0f}, east);
  for (const std::string& variant : variant_names) {
    const AlgorithmOutput output = make_embree_soft_shadow()->run(h.c, h.samples, variant);
    EXPECT_EQ(output.visible_fraction[beside_edge], 1.0f) << variant;
    EXPECT_EQ(output.visible_fraction[before_wall], 1.0f) << variant;
  }
  // A wall standing on the floor at x = 1 rises above the floor's plane: it shadows (a caster
  // straddling the receiver's plane, decided per hit).
  h.add_triangle({1, 0, -4}, {1, 0, 4}, {1, 2, 0});
  for (const std::string& variant : variant_names) {
    const AlgorithmOutput output = make_embree_soft_shadow()->run(h.c, h.samples, variant);
    EXPECT_EQ(output.visible_fraction[before_wall], 0.0f) << variant;
  }
}

// The default soft fixture, the exact oracle on every 12th regular sample (the algorithm only
// needs the samples it answers).
struct SoftFixture {
  Case c;
  ViewSamples samples;
};

const SoftFixture& foliage() {
  static const SoftFixture fixture = [] {
    SoftFixture f{make_fixture("foliage.10k"), {}};
    f.samples = testing::every_nth_regular(generate_view_samples(f.c), 12);
    return f;
  }();
  return fixture;
}

TEST(EmbreeSoftShadow, ErrorAgainstTheExactOracleFallsWithTheNumberOfRays) {
  const SoftFixture& f = foliage();
  const SoftShadowTruth truth = exact_soft_shadow_oracle(f.c, f.samples);
  const auto algorithm = make_embree_soft_shadow();
  std::map<std::string, double> mean_error, rms_error;
  std::printf("| variant | mean abs e | RMS | max | penumbra share | verdict |\n");
  for (const std::string& variant : variant_names) {
    const AlgorithmOutput output = algorithm->run(f.c, f.samples, variant);
    const SoftShadowComparison r =
        compare_soft_shadows(output.visible_fraction, truth, algorithm->soft_error_budget(variant));
    std::size_t penumbra = 0, compared = 0;
    for (std::size_t i = 0; i < truth.visible_fraction.size(); ++i) {
      if (!truth.compared[i]) continue;
      ++compared;
      penumbra += truth.visible_fraction[i] > 0.0 && truth.visible_fraction[i] < 1.0;
    }
    std::printf("| %s | %.5f | %.5f | %.4f | %.3f | %s |\n", variant.c_str(), r.mean_abs_error,
                r.rms_error, r.max_abs_error, double(penumbra) / double(compared),
                std::string(verdict_name(r.verdict)).c_str());
    EXPECT_EQ(r.verdict, Verdict::pass) << variant << ": " << r.reason;
    EXPECT_GT(penumbra, 100u);
    mean_error[variant] = r.mean_abs_error;
    rms_error[variant] = r.rms_error;
  }
  // Stratified sampling: four times the rays, at least halve the error (it falls faster than
  // 1 / sqrt(N) where few strata are cut by a shadow edge).
  EXPECT_LT(mean_error["rays64"], 0.75 * mean_error["rays16"]);
  EXPECT_LT(mean_error["rays256"], 0.75 * mean_error["rays64"]);
  EXPECT_LT(rms_error["rays64"], rms_error["rays16"]);
  EXPECT_LT(rms_error["rays256"], rms_error["rays64"]);
}

TEST(EmbreeSoftShadow, DeterministicForAnyThreadCountAndSeeded) {
  const SoftFixture& f = foliage();
  const auto algorithm = make_embree_soft_shadow();
  Case one = f.c, two = f.c, reseeded = f.c;
  one.parameters.threads = 1;
  two.parameters.threads = 2;
  reseeded.parameters.threads = 2;
  reseeded.parameters.seed = f.c.parameters.seed + 1;
  const AlgorithmOutput a = algorithm->run(one, f.samples, "rays16");
  const AlgorithmOutput b = algorithm->run(two, f.samples, "rays16");
  EXPECT_EQ(a.visible_fraction, b.visible_fraction);
  EXPECT_EQ(a.counters, b.counters);
  const AlgorithmOutput c = algorithm->run(reseeded, f.samples, "rays16");
  EXPECT_NE(a.visible_fraction, c.visible_fraction);
}

}  // namespace
}  // namespace shadowcts
