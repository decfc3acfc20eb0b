// The exact soft-shadow oracle on hand-built scenes: unions (shared edges, overlaps), samples that
// are not compared, a caster in contact, determinism, and agreement with Embree ray sampling (which
// shares no code with the projection) on random scenes at the stiff angular radii.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "oracles/soft_shadow/disk_polygon_area.h"
#include "oracles/soft_shadow/exact_disk_union.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

using testing::sun_disk;
const glm::vec3 up{0.0f, 1.0f, 0.0f};

TEST(ExactUnion, SharedEdgeAcrossTheDiskIsCountedOnce) {
  // A quad at height 1 split along a diagonal through the disk centre, covering part of the disk:
  // the union must equal the quad alone (no gap along the shared edge, no double count).
  const ShadowLight light = sun_disk(up, 2.0);
  const float r = float(std::tan(double(light.angular_radius)));
  const glm::vec3 a{-0.5f * r, 1, -2 * r}, b{2 * r, 1, -2 * r}, c{2 * r, 1, 2 * r},
      d{-0.5f * r, 1, 2 * r};
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle(a, b, c);
  h.add_triangle(a, c, d);
  h.add_ground_sample({0, 0, 0});
  const double union_fraction = exact_soft_shadow_oracle(h.c, h.samples).visible_fraction[0];
  // The quad as one polygon in disk units (light straight up: x, z over r).
  DiskPolygon quad;
  quad.count = 4;
  int k = 0;
  const double tan_a = std::tan(double(light.angular_radius));
  for (const glm::vec3& v : {a, b, c, d})
    quad.corners[k++] = {double(v.z) / tan_a, double(v.x) / tan_a};
  const double expected = 1.0 - unit_disk_intersection_area(quad) / std::numbers::pi;
  EXPECT_NEAR(union_fraction, expected, 1e-12);
  // Summing the two triangles' closed forms gives the same here (they only share an edge) ...
  const double sum = 2.0 - single_triangle_visible_fraction(light, {0, 0, 0}, h.c.triangles[1]) -
                     single_triangle_visible_fraction(light, {0, 0, 0}, h.c.triangles[2]);
  EXPECT_NEAR(1.0 - sum, expected, 1e-12);
}

// A needle whose tip pokes into the disk leaves it through an arc shorter than the rounding of its
// ends to double: Green's theorem must take that arc as the tiny sweep it is, not as a whole turn
// (which added pi: the whole disk hidden; found at a wide sun, where the horizon lines of the
// receiver's coplanar neighbours cross the disk). Needles and slivers at every angle against the
// closed form.
TEST(ExactUnion, NeedlesLeavingTheDiskThroughTinyArcs) {
  std::size_t compared = 0;
  for (int step = 0; step < 96; ++step) {
    const double angle = 2.0 * std::numbers::pi * (step + 0.37) / 96.0;
    const glm::dvec2 u{std::cos(angle), std::sin(angle)}, v{-u.y, u.x};
    for (const double width : {1e-3, 1e-7, 1e-11, 1e-14}) {
      for (const double tip : {0.93, 1.0 - 1e-9}) {
        DiskPolygon needle;
        needle.count = 3;
        needle.corners[0] = 2.86 * u + width * v;
        needle.corners[1] = tip * u;
        needle.corners[2] = 2.86 * u - width * v;
        const double want = unit_disk_intersection_area(needle);
        EXPECT_NEAR(covered_disk_area({needle}).area, want, 1e-9)
            << "angle " << angle << ", width " << width << ", tip " << tip;
        ++compared;
      }
    }
  }
  // The polygon that hid a whole disk in the oracle: a ground triangle seen nearly edge-on from a
  // sample beside it, under an 80-degree sun.
  DiskPolygon sliver;
  sliver.count = 3;
  sliver.corners[0] = {2.8636791593740387, -1.4300252749903923};
  sliver.corners[1] = {1.7397007920301486, -0.63348830436446868};
  sliver.corners[2] = {0.93183590349426759, -0.060973503648079186};
  EXPECT_NEAR(covered_disk_area({sliver}).area, unit_disk_intersection_area(sliver), 1e-9);
  EXPECT_EQ(compared, 96u * 8u);
}

// A caster in the sample's own plane projects to no area: seen exactly edge-on, whatever the
// rounding of its light-space coordinates says. Samples exactly on the shared diagonal of two
// coplanar floor triangles (casters) and inside a third that overlaps the receiver, under suns
// wide enough that a half-plane of directions would cross the disk.
TEST(ExactUnion, CastersInTheSamplesPlaneHideNothing) {
  for (const double degrees : {2.0, 45.0, 80.0}) {
    const ShadowLight light = sun_disk({0.3f, 1.0f, 0.2f}, degrees);
    testing::HandBuiltCase h = testing::make_hand_built_case(light);
    h.add_triangle({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, testing::caster_ground_mesh);
    h.add_triangle({-1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, testing::caster_ground_mesh);
    h.add_triangle({-2, 0, -3}, {3, 0, 2}, {-3, 0, 2}, testing::caster_ground_mesh);
    for (int i = 0; i < 200; ++i) {
      const float t = -0.9f + 1.8f * float(i) / 199.0f;
      h.add_ground_sample({t, 0.0f, t});
      h.add_ground_sample({0.37f * t, 0.0f, -0.61f * t});
    }
    const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
    for (std::size_t i = 0; i < h.samples.samples.size(); ++i)
      ASSERT_EQ(truth.visible_fraction[i], 1.0) << degrees << " degrees, sample " << i;
  }
}

TEST(ExactUnion, OverlappingCastersOccludeOnce) {
  // ... but two casters both hiding the same half of the disk hide half of it, not all of it
  // (the post's argument against summing areas).
  const ShadowLight light = sun_disk(up, 2.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle({0, 1, -100}, {0, 1, 100}, {100, 1, 0});
  h.add_triangle({0, 2, -100}, {0, 2, 100}, {100, 2, 0});
  h.add_ground_sample({0, 0, 0});
  EXPECT_NEAR(exact_soft_shadow_oracle(h.c, h.samples).visible_fraction[0], 0.5, 1e-12);
}

TEST(ExactUnion, ReceiverAndNonCastersNeverOcclude) {
  const ShadowLight light = sun_disk(up, 2.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  const std::uint32_t roof = h.add_triangle({-1, 1, -1}, {1, 1, -1}, {0, 1, 1});
  h.add_sample({0, 1, 0}, roof);         // on the roof: its own triangle does not count
  h.add_ground_sample({0, 0, 0});        // under it: fully shadowed
  h.add_ground_sample({0.5f, 0, 0.5f});  // the ground is no caster
  h.samples.samples.push_back(h.samples.samples[1]);
  h.samples.samples.back().sample_class = SampleClass::back_facing;
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  EXPECT_EQ(truth.visible_fraction[0], 1.0);
  EXPECT_EQ(truth.visible_fraction[1], 0.0);
  EXPECT_EQ(truth.compared[3], 0);
  EXPECT_EQ(truth.visible_fraction[3], 1.0);  // not compared: 1 by definition
}

TEST(StiffInputs, CasterOneMillionthInFrontOfTheReceiver) {
  const ShadowLight light = sun_disk({0.2f, 1.0f, 0.1f}, 2.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle({-1, 1e-6f, -1}, {1, 1e-6f, -1}, {0, 1e-6f, 1});
  h.add_ground_sample({0, 0, 0});
  h.add_ground_sample({4, 0, 4});
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  EXPECT_EQ(truth.visible_fraction[0], 0.0);
  // A band move of ~1e-4 can put the sample above the caster: ambiguous, and said so.
  EXPECT_EQ(truth.band_sensitivity[0], 1.0);
  EXPECT_EQ(truth.robust[0], 0);
  EXPECT_EQ(truth.visible_fraction[1], 1.0);
  EXPECT_EQ(truth.robust[1], 1);
}

// Random blockers over a receiving ground, samples under them.
testing::HandBuiltCase random_soft_scene(std::uint64_t seed, const ShadowLight& light, int blockers,
                                         float size, int sample_count) {
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < blockers; ++i) {
    const glm::vec3 centre{-2 + 4 * unit(random), 0.3f + 2 * unit(random), -2 + 4 * unit(random)};
    auto corner = [&] {
      return centre +
             size * glm::vec3(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f);
    };
    h.add_triangle(corner(), corner(), corner());
  }
  const glm::vec3 d = glm::normalize(light.direction);
  for (int s = 0; s < sample_count; ++s) {
    // Under the blockers along the light, so most samples see some of them.
    const glm::vec3 q{-2 + 4 * unit(random), 1.0f, -2 + 4 * unit(random)};
    const glm::vec3 p = q - (q.y / d.y) * d;
    h.add_ground_sample({p.x, 0.0f, p.z});
  }
  return h;
}

TEST(ExactVsSampled, RandomScenesAtStiffRadii) {
  for (double degrees : {0.27, 2.0, 10.0, 45.0}) {
    const ShadowLight light = sun_disk({0.3f, 1.0f, 0.2f}, degrees);
    testing::HandBuiltCase h = random_soft_scene(11, light, 60, 0.8f, 120);
    const SoftShadowTruth exact = exact_soft_shadow_oracle(h.c, h.samples);
    const SoftShadowTruth sampled = sampled_soft_shadow_oracle(h.c, h.samples, 4096);
    double sum = 0.0;
    int penumbra = 0;
    for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
      EXPECT_NEAR(exact.visible_fraction[i], sampled.visible_fraction[i], sampled.error_bound[i])
          << degrees << " degrees, sample " << i;
      sum += std::fabs(exact.visible_fraction[i] - sampled.visible_fraction[i]);
      penumbra += exact.visible_fraction[i] > 0.0 && exact.visible_fraction[i] < 1.0;
    }
    EXPECT_LT(sum / double(h.samples.samples.size()), 0.005) << degrees;
    EXPECT_GE(penumbra, 5) << degrees;
  }
}

TEST(ExactOracle, DeterministicForAnyThreadCount) {
  const ShadowLight light = sun_disk({0.3f, 1.0f, 0.2f}, 3.0);
  testing::HandBuiltCase h = random_soft_scene(5, light, 80, 0.6f, 300);
  h.c.parameters.threads = 1;
  const SoftShadowTruth one = exact_soft_shadow_oracle(h.c, h.samples);
  h.c.parameters.threads = 2;
  const SoftShadowTruth two = exact_soft_shadow_oracle(h.c, h.samples);
  EXPECT_EQ(one.visible_fraction, two.visible_fraction);
  EXPECT_EQ(one.band_sensitivity, two.band_sensitivity);
  h.c.parameters.threads = 1;
  const SoftShadowTruth sampled_one = sampled_soft_shadow_oracle(h.c, h.samples, 64);
  h.c.parameters.threads = 2;
  EXPECT_EQ(sampled_one.visible_fraction,
            sampled_soft_shadow_oracle(h.c, h.samples, 64).visible_fraction);
}

// The runner chooses between the oracles by this estimate: at stride 1 it is what the exact
// oracle unites, sample by sample; at a larger stride, every stride-th sample's count times stride.
TEST(ExactOracle, WorkEstimateCountsWhatTheUnionsTake) {
  for (double degrees : {0.27, 10.0, 45.0}) {
    const ShadowLight light = sun_disk({0.3f, 1.0f, 0.2f}, degrees);
    testing::HandBuiltCase h = random_soft_scene(11, light, 60, 0.8f, 120);
    const SoftShadowTruth exact = exact_soft_shadow_oracle(h.c, h.samples);
    EXPECT_GT(exact.candidate_triangles, 0u) << degrees;
    const ExactSoftShadowWork all = estimate_exact_soft_shadow_work(h.c, h.samples, 1);
    EXPECT_EQ(all.projections, exact.candidate_triangles) << degrees;
    // Sample by sample (each alone, the others not compared): the sum of squares.
    double squares = 0.0;
    for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
      const std::uint64_t k =
          exact_soft_shadow_oracle(h.c,
                                   testing::every_nth_regular(h.samples, 1'000'000, 1'000'000 - i))
              .candidate_triangles;
      squares += double(k) * double(k);
    }
    EXPECT_EQ(all.squared_projections, squares) << degrees;
    std::uint64_t every_third = 0;
    for (int offset = 0; offset < 3; ++offset) {
      // The samples the estimate visits at stride 3 from `offset`: compare them alone.
      const ViewSamples kept = testing::every_nth_regular(h.samples, 3, (3 - offset) % 3);
      const std::uint64_t part = exact_soft_shadow_oracle(h.c, kept).candidate_triangles;
      if (offset == 0) {
        EXPECT_EQ(estimate_exact_soft_shadow_work(h.c, h.samples, 3).projections, 3 * part)
            << degrees;
      }
      every_third += part;
    }
    EXPECT_EQ(every_third, exact.candidate_triangles) << degrees;
  }
}

}  // namespace
}  // namespace shadowcts
