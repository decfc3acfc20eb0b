// The reference softtile's parts and behaviour: the post's disk masks and scanline rasterization,
// edge flipping for triangles crossing the fragment plane, the hard-shadow limit a -> 0, the tile
// overflow, light-facing culling of closed meshes, the sin(a) shortcut, determinism.
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "oracles/soft_shadow/soft_shadow_comparison.h"
#include "reference/softtile/disk_bitmask.h"
#include "reference/softtile/fragment_occlusion.h"
#include "reference/softtile/softtile_algorithm.h"
#include "reference/softtile/softtile_variant.h"
#include "shadowcts/geometry/disk_reach.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

using testing::sun_disk;

TEST(DiskBitmask, ThePostsSixteenBySixteenDisk) {
  const softtile::DiskBitmask mask(softtile::parse_variant("grid16"));
  EXPECT_EQ(mask.disk_cells(), 208);
  EXPECT_EQ(mask.rows(), 16);
  for (int r = 0; r < 16; ++r) EXPECT_EQ(mask.row(r), mask.row(15 - r)) << r;  // symmetric
  EXPECT_EQ(mask.row(0), 0x07e0u);
  EXPECT_EQ(mask.row(7), 0xffffu);
}

TEST(DiskBitmask, RowsOfThirtyOneBits) {
  for (int rows : {3, 5, 7, 15, 31}) {
    const softtile::DiskBitmask mask(softtile::parse_variant("rows" + std::to_string(rows)));
    // About the disk's share pi / 4 of the rows x 31 cells.
    const double share = double(mask.disk_cells()) / (rows * 31.0);
    EXPECT_NEAR(share, std::numbers::pi / 4.0, 0.12) << rows;
    for (int r = 0; r < rows; ++r) EXPECT_LT(mask.row(r), 1u << 31);
  }
}

TEST(DiskBitmask, HalfPlaneClearsTheCellsOnItsSide) {
  for (const char* name : {"grid16", "rows3", "rows31"}) {
    softtile::DiskBitmask mask(softtile::parse_variant(name));
    const int before = mask.disk_cells();
    // Inside: X >= 0.3 (edge x = 0.3, inside to the right). Two far edges close the triangle.
    mask.clear_triangle({glm::vec3(1, 0, -0.3f), glm::vec3(0, 1, 10), glm::vec3(0, -1, 10)});
    int expected_lit = 0;
    const softtile::DiskBitmask fresh(softtile::parse_variant(name));
    for (int r = 0; r < fresh.rows(); ++r)
      for (int col = 0; col < fresh.columns(); ++col) {
        const bool in_disk = fresh.row(r) >> (fresh.columns() - 1 - col) & 1u;
        const double x = -1.0 + (col + 0.5) * 2.0 / fresh.columns();
        expected_lit += in_disk && x < 0.3;
      }
    EXPECT_EQ(mask.lit_cells(), expected_lit) << name;
    EXPECT_LT(mask.lit_cells(), before);
  }
}

// The early-out by the triangle's light-space box (shadowcts/geometry/disk_reach.h) skips only
// triangles whose setup would clear no cell: triangles placed at the reach's boundary, a few ulps
// and a few margins either side, one vertex at the box's corner nearest the disk, with rotated
// grids, at scales 2^-40 to 2^40 and on every grid. Each one the early-out calls beside is set up
// anyway (reach_per_height infinity turns the early-out off) and must clear nothing.
TEST(Softtile, TrianglesBesideTheDisksReachClearNoCell) {
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t beside = 0, set_up = 0;  // called beside; of them, accepted by the setup alone
  for (const char* name : {"grid16", "rows3", "rows31", "post"}) {
    const softtile::Variant variant = softtile::parse_variant(name);
    for (int trial = 0; trial < 20000; ++trial) {
      const double scale = std::ldexp(1.0, int(random() % 81) - 40);
      const double a = (0.1 + 40.0 * std::abs(unit(random))) * std::numbers::pi / 180.0;
      softtile::FragmentSetup fragment;
      fragment.position = glm::vec3(glm::dvec3(unit(random), unit(random), unit(random)) * scale);
      fragment.inverse_scale =
          float(1.0 / (variant.sine_normalization ? std::sin(a) : std::tan(a)));
      fragment.reach_per_height = disk_reach_per_height(fragment.inverse_scale);
      if (trial % 2 == 1) {
        const double angle = 2.0 * std::numbers::pi * unit(random);
        fragment.cos_rotation = float(std::cos(angle));
        fragment.sin_rotation = float(std::sin(angle));
      }
      // The nearest corner: the disk's reach at the corner's height, times 1 + d, d from -1 (well
      // inside) through the margins (2^-8 and less) to 1 (well beside), on a random side.
      const double height = scale * (0.01 + std::abs(unit(random)));
      const double reach = height / double(fragment.inverse_scale);
      const double d = std::ldexp(unit(random), -int(random() % 12));
      const glm::dvec3 p(fragment.position);
      const double side = random() % 2 == 0 ? 1.0 : -1.0;
      const bool along_x = random() % 2 == 0;
      const double off = side * reach * (1.0 + d);
      const double across = reach * unit(random);
      glm::dvec3 corner = p + glm::dvec3(along_x ? off : across, along_x ? across : off, height);
      std::array<glm::vec3, 3> light_space;
      light_space[0] = glm::vec3(corner);
      for (int v = 1; v < 3; ++v) {
        // The other vertices farther out on that side, lower or below the fragment.
        const double out = side * scale * std::abs(unit(random));
        light_space[v] =
            glm::vec3(corner + glm::dvec3(along_x ? out : scale * unit(random),
                                          along_x ? scale * unit(random) : out,
                                          -height * std::abs(unit(random)) * (v == 2 ? 2.0 : 1.0)));
      }
      std::array<glm::vec3, 3> edges;
      if (softtile::triangle_edges(fragment, light_space, edges)) continue;
      softtile::FragmentSetup without = fragment;
      without.reach_per_height = std::numeric_limits<float>::infinity();
      const bool accepted_without = softtile::triangle_edges(without, light_space, edges);
      const float vertices[9] = {light_space[0].x, light_space[0].y, light_space[0].z,
                                 light_space[1].x, light_space[1].y, light_space[1].z,
                                 light_space[2].x, light_space[2].y, light_space[2].z};
      if (!beside_disk(fragment.position.x, fragment.position.y, fragment.position.z,
                       light_space_box(vertices), fragment.reach_per_height)) {
        EXPECT_FALSE(accepted_without) << name << ", trial " << trial;  // rejected by the setup
        continue;
      }
      ++beside;
      if (!accepted_without) continue;
      // The setup alone would have accepted it: its edges must leave every cell lit.
      softtile::DiskBitmask mask(variant);
      mask.clear_triangle(edges);
      ASSERT_EQ(mask.lit_cells(), mask.disk_cells())
          << name << ", trial " << trial << ": a triangle beside the reach cleared cells";
      ++set_up;
    }
  }
  // The early-out decided many of them, some that the setup alone accepts among them.
  EXPECT_GT(beside, 20000u);
  EXPECT_GT(set_up, 1000u);
}

// One caster over a non-caster ground, samples under it; softtile against the exact oracle.
SoftShadowComparison compare_on(const testing::HandBuiltCase& h, const std::string& variant,
                                AlgorithmOutput* output_out = nullptr) {
  const auto algorithm = make_softtile();
  AlgorithmOutput output = algorithm->run(h.c, h.samples, variant);
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  const SoftShadowComparison r =
      compare_soft_shadows(output.visible_fraction, truth, softtile_error_budget(variant));
  if (output_out) *output_out = std::move(output);
  return r;
}

TEST(Softtile, TrianglesCrossingTheFragmentPlaneAgreeWithTheClippedExactAnswer) {
  // Big leaning triangles with one vertex below the samples' plane perpendicular to d: edge
  // flipping must give the clipped projection (a wrong flip clears the complement of the disk).
  const ShadowLight light = sun_disk({0.0f, 1.0f, 0.0f}, 5.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle({-0.3f, 1.0f, 0.2f}, {0.4f, 1.5f, 0.1f}, {0.05f, -1.0f, -0.2f});
  for (int i = 0; i < 64; ++i)
    h.add_ground_sample(
        {-0.2f + 0.4f * float(i % 8) / 7.0f, 0.0f, -0.2f + 0.4f * float(i / 8) / 7.0f});
  h.samples.width = 8;
  h.samples.height = 8;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    h.samples.samples[i].pixel_x = std::uint32_t(i % 8);
    h.samples.samples[i].pixel_y = std::uint32_t(i / 8);
  }
  for (const char* variant : {"grid16", "rows31", "grid16+rot"}) {
    const SoftShadowComparison r = compare_on(h, variant);
    EXPECT_EQ(r.verdict, Verdict::pass) << variant << ": " << r.reason;
    EXPECT_LT(r.max_abs_error, 0.06) << variant;
  }
}

TEST(Softtile, TendsToTheHardShadowAsTheDiskShrinks) {
  // Robust samples of the hard-shadow oracle (directional light along the disk's centre) are
  // fully lit or fully shadowed once the disk is small enough.
  const glm::vec3 direction{0.3f, 1.0f, 0.2f};
  // No samples at the images of blocker vertices: the 14 band moves can all miss a sharp corner
  // the ray passes within rounding of, so such a sample can be "robust" for hard shadows while any
  // disk, however small, sees part of the corner (and the exact soft oracle agrees with softtile).
  testing::HandBuiltCase hard = testing::make_random_case(
      17, 8, 120, 1.0f, 800, testing::directional_light(direction), /*vertex_images=*/false);
  const HardShadowTruth hard_truth = exact_hard_shadow_oracle(hard.c, hard.samples);
  const auto algorithm = make_softtile();
  std::size_t previous_mismatches = hard.samples.samples.size();
  for (double radians : {1e-2, 1e-3, 1e-5}) {
    Case soft = hard.c;
    soft.light = sun_disk(direction, 1.0);
    soft.light->angular_radius = float(radians);
    const AlgorithmOutput output = algorithm->run(soft, hard.samples, "grid16");
    std::size_t mismatches = 0, robust = 0;
    for (std::size_t i = 0; i < hard.samples.samples.size(); ++i) {
      if (hard_truth.band[i] != BandClass::robust_lit &&
          hard_truth.band[i] != BandClass::robust_shadowed)
        continue;
      ++robust;
      const float expected = hard_truth.shadowed[i] ? 0.0f : 1.0f;
      mismatches += output.visible_fraction[i] != expected;
    }
    ASSERT_GT(robust, 500u);
    EXPECT_LE(mismatches, previous_mismatches) << radians;
    previous_mismatches = mismatches;
    if (radians == 1e-5) {
      EXPECT_EQ(mismatches, 0u);
    }
  }
}

TEST(Softtile, TileOverflowIsProcessedAndCounted) {
  // 3000 small stacked casters over one tile: more than the tile's buffer holds.
  const ShadowLight light = sun_disk({0.0f, 1.0f, 0.0f}, 2.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  std::mt19937_64 random(4);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 centre{0.3f * unit(random), 1.5f + unit(random), 0.3f * unit(random)};
    h.add_triangle(centre + glm::vec3(-0.3f, 0, -0.3f), centre + glm::vec3(0.3f, 0, -0.3f),
                   centre + glm::vec3(0, 0.01f, 0.3f));
  }
  for (int i = 0; i < 16; ++i)
    h.add_ground_sample(
        {-0.1f + 0.2f * float(i % 4) / 3.0f, 0.0f, -0.1f + 0.2f * float(i / 4) / 3.0f});
  h.samples.width = 4;
  h.samples.height = 4;
  for (std::size_t i = 0; i < 16; ++i) {
    h.samples.samples[i].pixel_x = std::uint32_t(i % 4);
    h.samples.samples[i].pixel_y = std::uint32_t(i / 4);
  }
  AlgorithmOutput output;
  const SoftShadowComparison r = compare_on(h, "grid16", &output);
  EXPECT_EQ(r.verdict, Verdict::pass) << r.reason;
  std::uint64_t overflowing = 0, batches = 0;
  for (const auto& [name, value] : output.counters) {
    if (name == "overflowing_tiles") overflowing = value;
    if (name == "overflow_batches") batches = value;
  }
  EXPECT_EQ(overflowing, 1u);
  EXPECT_GE(batches, 1u);
}

TEST(Softtile, LightFacingTrianglesOfClosedMeshesAreDroppedWithoutChangingTheResult) {
  const ShadowLight light = sun_disk({0.2f, 1.0f, 0.1f}, 3.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  testing::add_pyramid_fan(h);  // four faces around an apex: light-facing and not
  // Close it with the base (outward: facing down).
  h.add_triangle({-1, 2, -1}, {1, 2, 1}, {1, 2, -1});
  h.add_triangle({-1, 2, -1}, {-1, 2, 1}, {1, 2, 1});
  for (int i = 0; i < 64; ++i)
    h.add_ground_sample(
        {-1.6f + 3.2f * float(i % 8) / 7.0f, 0.0f, -1.6f + 3.2f * float(i / 8) / 7.0f});
  const auto algorithm = make_softtile();
  const AlgorithmOutput open = algorithm->run(h.c, h.samples, "grid16");
  h.c.meshes[testing::blocker_mesh].closed = true;
  const AlgorithmOutput closed = algorithm->run(h.c, h.samples, "grid16");
  EXPECT_EQ(open.visible_fraction, closed.visible_fraction);
  std::uint64_t dropped = 0;
  for (const auto& [name, value] : closed.counters)
    if (name == "gather_light_facing_dropped") dropped = value;
  EXPECT_GE(dropped, 2u);
}

TEST(Softtile, TheSineShortcutCostsAccuracyAtLargeDisks) {
  // At 30 degrees the post's sin(a) normalization sees the disk of tangent radius sin(a) instead
  // of tan(a), missing a share sin^2(a) = 1/4 of it: its error shows against the cone-exact tan(a).
  const ShadowLight light = sun_disk({0.2f, 1.0f, 0.1f}, 30.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  h.add_triangle({-4, 1, -4}, {4, 1, -4}, {0.0f, 1, 0.0f});
  for (int i = 0; i < 400; ++i)
    h.add_ground_sample(
        {-1.0f + 2.0f * float(i % 20) / 19.0f, 0.0f, -1.0f + 2.0f * float(i / 20) / 19.0f});
  const SoftShadowComparison post = compare_on(h, "post");
  const SoftShadowComparison exact_scale = compare_on(h, "grid16+rot");
  EXPECT_GT(post.mean_abs_error, exact_scale.mean_abs_error);
}

// The per-sample budget is one edge's worst case (rows + columns cells), not a bound for several
// edges: five slivers 1e-5 wide at height 1, under a 5-degree sun straight overhead, lie along
// light-space x at the centres of rows 5 to 9 of the 16-row grid (-1 + (r + 1/2) / 8, times
// tan(a)). Seen from ground samples within 5e-6 of the origin, each sliver's shadow runs through a
// whole row of the unrotated mask's cell centres, so grid16 clears five rows where the slivers hide
// almost nothing of the disk. The rotated grid and the 31-row mask, whose rows lie elsewhere, stay
// within their budgets (docs/soft-shadow-budgets.md).
TEST(Softtile, ThinSlatsAlongCellCentreRowsExceedTheOneEdgeBudget) {
  testing::HandBuiltCase h = testing::make_hand_built_case(sun_disk({0.0f, 1.0f, 0.0f}, 5.0));
  // A ground of about unit size, so that the band (2^-16 of the scale) moves the slivers' shadows
  // by less than their width and the samples stay robust.
  h.c.triangles[h.ground] =
      Triangle{{-0.6f, 0.0f, -0.5f}, {0.6f, 0.0f, -0.5f}, {0.0f, 0.0f, 0.6f}, testing::ground_mesh};
  const double tan_radius = std::tan(double(h.c.light->angular_radius));
  const double width = 1e-5;
  for (int row = 5; row <= 9; ++row) {
    const double x = tan_radius * (-1.0 + (row + 0.5) / 8.0) - 0.5 * width;
    h.add_triangle({float(x), 1.0f, -0.12f}, {float(x), 1.0f, 0.12f},
                   {float(x + width), 1.0f, 0.0f});
  }
  for (int i = -32; i < 32; ++i) h.add_ground_sample({float(i) * 1e-6f, 0.0f, 0.0f});
  // The samples whose view of every sliver holds a row's centres, and there the exact disk.
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  std::size_t aligned = 0;
  for (std::size_t s = 0; s < h.samples.samples.size(); ++s) {
    ASSERT_TRUE(truth.robust[s]) << "sample " << s;
    const glm::dvec3 p(h.samples.samples[s].position);
    bool on_rows = true;
    for (std::size_t k = 1; k < h.c.triangles.size(); ++k) {
      const Triangle& t = h.c.triangles[k];
      const double low = (double(t.v0.x) - p.x) / ((double(t.v0.y) - p.y) * tan_radius);
      const double high = (double(t.v2.x) - p.x) / ((double(t.v2.y) - p.y) * tan_radius);
      const double centre = -1.0 + (std::floor((low + 1.0) * 8.0) + 0.5) / 8.0;
      on_rows = on_rows && low <= centre && centre <= high;
    }
    if (!on_rows) continue;
    ++aligned;
    EXPECT_GT(truth.visible_fraction[s], 0.99) << "sample " << s;
  }
  EXPECT_GE(aligned, 5u);
  const SoftShadowComparison grid = compare_on(h, "grid16");
  EXPECT_EQ(grid.verdict, Verdict::fail) << grid.reason;
  EXPECT_GE(grid.over_budget, 5u);
  EXPECT_GT(grid.max_abs_error, 0.3);
  for (const char* variant : {"grid16+rot", "rows31"}) {
    const SoftShadowComparison r = compare_on(h, variant);
    EXPECT_EQ(r.verdict, Verdict::pass) << variant << ": " << r.reason;
  }
}

TEST(Softtile, DeterministicForAnyThreadCount) {
  testing::HandBuiltCase h =
      testing::make_random_case(23, 8, 100, 1.0f, 600, sun_disk({0.3f, 1.0f, 0.2f}, 3.0));
  h.samples.width = 30;
  h.samples.height = std::uint32_t(h.samples.samples.size() + 29) / 30;
  h.samples.samples.resize(std::size_t(h.samples.width) * h.samples.height, ViewSample{});
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    h.samples.samples[i].pixel_x = std::uint32_t(i % 30);
    h.samples.samples[i].pixel_y = std::uint32_t(i / 30);
  }
  const auto algorithm = make_softtile();
  for (const char* variant : {"grid16+rot", "rows31+rot"}) {
    h.c.parameters.threads = 1;
    const AlgorithmOutput one = algorithm->run(h.c, h.samples, variant);
    h.c.parameters.threads = 2;
    const AlgorithmOutput two = algorithm->run(h.c, h.samples, variant);
    EXPECT_EQ(one.visible_fraction, two.visible_fraction) << variant;
    EXPECT_EQ(one.counters, two.counters) << variant;
  }
}

// The fragment setup's edge functions are homogeneous in light-space coordinates, and light
// space is normalized by a power of two: the same case at scales 2^-60 .. 2^60 gives the same
// masks and counters, where float32 products of three coordinates would otherwise overflow (all
// lit from about 2^40 on) or lose precision to underflow.
TEST(Softtile, SameAnswersAtEveryPowerOfTwoScale) {
  const testing::HandBuiltCase h =
      testing::make_random_case(29, 8, 100, 1.0f, 600, sun_disk({0.3f, 1.0f, 0.2f}, 3.0));
  const auto algorithm = make_softtile();
  for (const char* variant : {"grid16+rot", "rows31"}) {
    const AlgorithmOutput unit = algorithm->run(h.c, h.samples, variant);
    std::size_t shadowed = 0;
    for (const float v : unit.visible_fraction) shadowed += v < 1.0f ? 1 : 0;
    EXPECT_GT(shadowed, 100u) << variant;
    for (const int k : {-60, -24, 24, 60}) {
      const testing::HandBuiltCase scaled = testing::scaled_by_power_of_two(h, k);
      const AlgorithmOutput output = algorithm->run(scaled.c, scaled.samples, variant);
      EXPECT_EQ(output.visible_fraction, unit.visible_fraction) << variant << " at 2^" << k;
      EXPECT_EQ(output.counters, unit.counters) << variant << " at 2^" << k;
    }
  }
}

TEST(Softtile, OnlySunDisks) {
  const auto algorithm = make_softtile();
  testing::HandBuiltCase h =
      testing::make_hand_built_case(testing::directional_light({0.0f, 1.0f, 0.0f}));
  h.add_ground_sample({0, 0, 0});
  EXPECT_TRUE(algorithm->unsupported_reason(h.c, h.samples, "grid16").has_value());
  h.c.light = sun_disk({0.0f, 1.0f, 0.0f}, 1.0);
  EXPECT_FALSE(algorithm->unsupported_reason(h.c, h.samples, "grid16").has_value());
  EXPECT_THROW(algorithm->run(h.c, h.samples, "grid17"), std::invalid_argument);
  EXPECT_THROW(softtile_error_budget("grid17"), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
