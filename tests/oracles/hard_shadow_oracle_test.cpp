// Both hard-shadow oracles on hand-built configurations whose answer and band are known exactly,
// and against each other on random cases.
#include "shadowcts/hard_shadow_oracle.h"

#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

using testing::add_pyramid_fan;
using testing::directional_light;
using testing::HandBuiltCase;
using testing::make_hand_built_case;
using testing::point_light;

struct Truths {
  HardShadowTruth exact, embree;
};

Truths run_both(const HandBuiltCase& h) {
  return {exact_hard_shadow_oracle_with_exponents(h.c, h.samples),
          embree_hard_shadow_oracle(h.c, h.samples)};
}

void expect_robustly_shadowed(const Truths& t, std::size_t i) {
  EXPECT_EQ(t.exact.shadowed[i], 1) << "sample " << i;
  EXPECT_EQ(t.exact.band[i], BandClass::robust_shadowed) << "sample " << i;
  EXPECT_EQ(t.exact.robust_exponent[i], band_max_exponent) << "sample " << i;
  EXPECT_EQ(t.embree.shadowed[i], 1) << "sample " << i;
  EXPECT_EQ(t.embree.band[i], BandClass::robust_shadowed) << "sample " << i;
}

void expect_robustly_lit(const Truths& t, std::size_t i) {
  EXPECT_EQ(t.exact.shadowed[i], 0) << "sample " << i;
  EXPECT_EQ(t.exact.band[i], BandClass::robust_lit) << "sample " << i;
  EXPECT_EQ(t.exact.robust_exponent[i], band_max_exponent) << "sample " << i;
  EXPECT_EQ(t.embree.shadowed[i], 0) << "sample " << i;
  EXPECT_EQ(t.embree.band[i], BandClass::robust_lit) << "sample " << i;
}

TEST(HardShadowOracles, RecordHowTheyWereObtained) {
  auto h = make_hand_built_case(point_light({0, 8, 0}));
  h.add_ground_sample({0, 0, 0});
  const Truths t = run_both(h);
  EXPECT_TRUE(t.exact.exact);
  EXPECT_FALSE(t.embree.exact);
  EXPECT_EQ(t.exact.method.rfind("exact", 0), 0u) << t.exact.method;
  EXPECT_EQ(t.embree.method.rfind("estimated", 0), 0u) << t.embree.method;
  EXPECT_EQ(t.exact.eps_rel, 0x1p-16);
  EXPECT_EQ(t.exact.tau, 0x1p-16 * h.c.scale());
}

TEST(HardShadowOracles, RayThroughAnEdgeSharedInAClosedFanIsRobustlyShadowed) {
  auto vertical = make_hand_built_case(point_light({0.5f, 8, 0.5f}));
  add_pyramid_fan(vertical);
  const std::size_t through_edge = vertical.add_ground_sample({0.5f, 0, 0.5f});
  expect_robustly_shadowed(run_both(vertical), through_edge);

  // Oblique: from the origin through the edge point (0.5, 2.5, 0.5) at t = 1/4.
  auto oblique = make_hand_built_case(point_light({2, 10, 2}));
  add_pyramid_fan(oblique);
  expect_robustly_shadowed(run_both(oblique), oblique.add_ground_sample({0, 0, 0}));

  auto directional = make_hand_built_case(directional_light({1, 5, 1}));
  add_pyramid_fan(directional);
  expect_robustly_shadowed(run_both(directional), directional.add_ground_sample({0, 0, 0}));
}

TEST(HardShadowOracles, RayThroughTheFansSharedVertexIsRobustlyShadowed) {
  auto vertical = make_hand_built_case(point_light({0, 8, 0}));
  add_pyramid_fan(vertical);
  expect_robustly_shadowed(run_both(vertical), vertical.add_ground_sample({0, 0, 0}));

  // Oblique: from (-0.5, 0, -0.25) through the apex (0, 3, 0) at t = 1/2.
  auto oblique = make_hand_built_case(point_light({0.5f, 6, 0.25f}));
  add_pyramid_fan(oblique);
  expect_robustly_shadowed(run_both(oblique), oblique.add_ground_sample({-0.5f, 0, -0.25f}));

  auto directional = make_hand_built_case(directional_light({0, 1, 0}));
  add_pyramid_fan(directional);
  expect_robustly_shadowed(run_both(directional), directional.add_ground_sample({0, 0, 0}));
}

// The pyramid fan with one of its triangles split at the midpoint m = (0.5, 2.5, -0.5) of an edge
// it shares with its neighbour: the neighbour's edge now has a T-junction at m. The fan is still
// closed, so rays through either part of that edge or through m itself stay blocked under every
// perturbation: robust (the band's closure test cuts edges at T-junctions).
TEST(HardShadowOracles, RayThroughAnEdgeWithATJunctionIsRobustlyShadowed) {
  const glm::vec3 apex{0, 3, 0};
  const glm::vec3 rim[4] = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  const glm::vec3 m{0.5f, 2.5f, -0.5f};  // on the edge rim[1] - apex
  const glm::vec3 through[] = {m, {0.25f, 2.75f, -0.25f}, {0.75f, 2.25f, -0.75f}};
  for (const glm::vec3& x : through)
    for (const bool directional : {false, true}) {
      auto h = make_hand_built_case(directional ? directional_light({0, 1, 0})
                                                : point_light({x.x, 8, x.z}));
      h.add_triangle(apex, rim[0], m);  // triangle (apex, rim[0], rim[1]) split at m
      h.add_triangle(m, rim[0], rim[1]);
      for (int i = 1; i < 4; ++i) h.add_triangle(apex, rim[i], rim[(i + 1) % 4]);
      const std::size_t sample = h.add_ground_sample({x.x, 0, x.z});
      // Exact oracle only: float rays need not be watertight at a T-junction.
      const HardShadowTruth exact = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
      EXPECT_EQ(exact.shadowed[sample], 1) << x.x << " " << directional;
      EXPECT_EQ(exact.band[sample], BandClass::robust_shadowed) << x.x << " " << directional;
      EXPECT_EQ(exact.robust_exponent[sample], band_max_exponent) << x.x << " " << directional;
    }
}

TEST(HardShadowOracles, RayThroughASilhouetteEdgeOrVertexIsAmbiguous) {
  // (light, sample): through the boundary edge z = -1, and through the vertex (0, 2, 1).
  const std::pair<ShadowLight, glm::vec3> configurations[] = {
      {point_light({0, 8, -1}), {0, 0, -1}},          {point_light({0, 8, 1}), {0, 0, 1}},
      {directional_light({0, 1, 0}), {0, 0, -1}},     {directional_light({0, 1, 0}), {0, 0, 1}},
      {directional_light({1, 4, 0}), {-0.5f, 0, -1}},
  };
  for (const auto& [light, position] : configurations) {
    auto h = make_hand_built_case(light);
    h.add_triangle({-1, 2, -1}, {1, 2, -1}, {0, 2, 1});
    const std::size_t i = h.add_ground_sample(position);
    const Truths t = run_both(h);
    EXPECT_EQ(t.exact.shadowed[i], 1);  // closed triangles
    EXPECT_EQ(t.exact.band[i], BandClass::ambiguous);
    // Every move away from the triangle, however small, lights it.
    EXPECT_EQ(t.exact.robust_exponent[i], ambiguous_at_every_exponent);
    EXPECT_EQ(t.embree.band[i], BandClass::ambiguous);
  }
}

// The sample's ray passes 2^-30 beside the vertex (0, 2, 0) of a triangle whose shadow near that
// vertex is a wedge between the directions (1, 0.25) and (1, 0.375) in xz, 14 to 21 degrees. No
// move direction of the band (multiples of 45 degrees in xz) points into the wedge at any length,
// yet every cube of moves around the sample holds points of the wedge, where a float
// implementation may legitimately see the vertex (2^-30 is far below float resolution at 2): the
// sample is ambiguous at every eps_rel (the band tests the whole cube, not the 14 moves).
TEST(HardShadowOracles, ThinWedgeApexIsAmbiguous) {
  for (const ShadowLight& light : {point_light({0, 8, 0}), directional_light({0, 1, 0})}) {
    auto h = make_hand_built_case(light);
    h.add_triangle({0, 2, 0}, {1, 2, 0.25f}, {1, 2, 0.375f});
    const std::size_t i = h.add_ground_sample({-0x1p-30f, 0, 0});
    const HardShadowTruth exact = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
    EXPECT_EQ(exact.shadowed[i], 0);
    EXPECT_EQ(exact.band[i], BandClass::ambiguous);
    EXPECT_EQ(exact.robust_exponent[i], ambiguous_at_every_exponent);
  }
}

// The same wedge lit inside a shadow: a fan of three triangles around (0, 2, 0) covers every
// direction except the wedge between (1, 0.25) and (1, 0.375). The sample's ray passes 2^-30
// beside the fan's apex, on the covered side: shadowed, and every one of the 14 moves stays
// shadowed at every length, but every cube of moves holds lit points of the wedge.
TEST(HardShadowOracles, ThinLitWedgeInsideAShadowIsAmbiguous) {
  for (const ShadowLight& light : {point_light({0, 8, 0}), directional_light({0, 1, 0})}) {
    auto h = make_hand_built_case(light);
    const glm::vec3 apex{0, 2, 0};
    h.add_triangle(apex, {1, 2, 0.375f}, {-1, 2, 1});
    h.add_triangle(apex, {-1, 2, 1}, {-1, 2, -1});
    h.add_triangle(apex, {-1, 2, -1}, {1, 2, 0.25f});
    const std::size_t i = h.add_ground_sample({-0x1p-30f, 0, 0});
    const HardShadowTruth exact = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
    EXPECT_EQ(exact.shadowed[i], 1);
    EXPECT_EQ(exact.band[i], BandClass::ambiguous);
    EXPECT_EQ(exact.robust_exponent[i], ambiguous_at_every_exponent);
    // Away from the apex, deep inside the fan's shadow, the sample is robust again.
    const std::size_t inside = h.add_ground_sample({-0.5f, 0, 0});
    EXPECT_EQ(exact_hard_shadow_oracle_with_exponents(h.c, h.samples).band[inside],
              BandClass::robust_shadowed);
  }
}

TEST(HardShadowOracles, SegmentInACastersPlane) {
  auto h = make_hand_built_case(point_light({0, 8, 0}));
  h.add_triangle({0, 1, -1}, {0, 1, 1}, {0, 3, 0});  // in the plane x = 0, like the segment
  const std::size_t through = h.add_ground_sample({0, 0, 0});
  const Truths t = run_both(h);
  EXPECT_EQ(t.exact.shadowed[through], 1);
  EXPECT_EQ(t.exact.band[through], BandClass::ambiguous);  // a move along x clears it
  // (Embree misses triangles seen edge-on: that is why such samples are ambiguous.)

  // Coplanar but beside the triangle, and grazing the plane at the light only.
  auto beside = make_hand_built_case(point_light({0, 8, 2}));
  beside.add_triangle({0, 1, -1}, {0, 1, 1}, {0, 3, 0});
  expect_robustly_lit(run_both(beside), beside.add_ground_sample({0, 0, 2}));
  auto grazing = make_hand_built_case(point_light({0, 2, 2}));
  grazing.add_triangle({0, 1, -1}, {0, 1, 1}, {0, 3, 0});
  expect_robustly_lit(run_both(grazing), grazing.add_ground_sample({1, 0, 0}));
}

TEST(HardShadowOracles, LightInACastersPlane) {
  auto beside = make_hand_built_case(point_light({0, 8, 0}));
  beside.add_triangle({1, 8, -1}, {3, 8, -1}, {2, 8, 1});
  expect_robustly_lit(run_both(beside), beside.add_ground_sample({0, 0, 0}));

  // The light lies on a caster: by the closed definition every segment ends on it.
  auto on = make_hand_built_case(point_light({0, 8, 0}));
  on.add_triangle({-1, 8, -1}, {1, 8, -1}, {0, 8, 1});
  const std::size_t i = on.add_ground_sample({3, 0, 0});
  const HardShadowTruth exact = exact_hard_shadow_oracle_with_exponents(on.c, on.samples);
  EXPECT_EQ(exact.shadowed[i], 1);
  EXPECT_EQ(exact.band[i], BandClass::robust_shadowed);
}

// A point light far beyond the triangles: S (1e25) is the light's, so Embree's scene is sized by
// the triangles and the ray towards the light gets its direction scaled by a power of two (beyond
// Embree's 1.8e18 assertion as it is). Before, the scene went in at 2^-84, denormal-sized, and
// every ray missed.
TEST(HardShadowOracles, RaysReachAFarPointLight) {
  HandBuiltCase h = make_hand_built_case(point_light({0.25f, 1e25f, 0.5f}));
  add_pyramid_fan(h);
  const std::size_t under = h.add_ground_sample({0.1f, 0, 0.2f});
  const std::size_t beside = h.add_ground_sample({5, 0, 5});
  const Truths t = run_both(h);
  EXPECT_EQ(t.exact.shadowed[under], 1);
  EXPECT_EQ(t.embree.shadowed[under], 1);
  EXPECT_EQ(t.exact.shadowed[beside], 0);
  EXPECT_EQ(t.embree.shadowed[beside], 0);
}

TEST(HardShadowOracles, ZeroAreaCastersNeverShadow) {
  for (const ShadowLight& light : {point_light({0, 8, 0}), directional_light({0, 1, 0})}) {
    auto h = make_hand_built_case(light);
    h.add_triangle({-1, 2, 0}, {1, 2, 0}, {0, 2, 0});   // collinear, across the segment
    h.add_triangle({-1, 3, 0}, {-1, 3, 0}, {1, 3, 0});  // a repeated vertex
    h.add_triangle({0, 4, 0}, {0, 4, 0}, {0, 4, 0});    // a point on the segment
    expect_robustly_lit(run_both(h), h.add_ground_sample({0, 0, 0}));
  }
}

TEST(HardShadowOracles, ReceiverNeverShadowsItsOwnSample) {
  for (const ShadowLight& light :
       {point_light({0, 8, 0}), directional_light({0, 1, 0}), point_light({0, -8, 0})}) {
    auto h = make_hand_built_case(light);
    const std::uint32_t receiver = h.add_triangle({-1, 2, -1}, {1, 2, -1}, {0, 2, 1});
    const std::size_t on_receiver = h.add_sample({0, 2, 0}, receiver);
    // The same position with another receiver: the caster then contains the sample, and shadows
    // it where the caster lies on the light's side of that receiver's plane y = 0 (the receiver
    // half-space rule): for the lights above, not for the one below.
    const std::size_t other = h.add_sample({0, 2, 0}, h.ground);
    const Truths t = run_both(h);
    expect_robustly_lit(t, on_receiver);
    const int expected = light.kind == ShadowLightKind::point && light.position.y < 0 ? 0 : 1;
    EXPECT_EQ(t.exact.shadowed[other], expected);
    EXPECT_EQ(t.embree.shadowed[other], expected);
  }
}

// The receiver half-space rule (DESIGN.md): samples within rounding of their receiver's plane,
// even below it, are not shadowed by a coplanar neighbour or by the next face of a convex closed
// mesh, and are robust; a wall standing on the floor still shadows the floor behind it.
TEST(HardShadowOracles, CoplanarNeighboursAndConvexNextFacesNeverShadowTheirReceiversSamples) {
  for (const ShadowLight& light :
       {point_light({0.5f, 8, 0.25f}), directional_light({0.1f, 1, 0})}) {
    auto h = make_hand_built_case(light);
    // Floor cells at y = 1 sharing the edge x = 0 (left: two triangles, right: two), and the next
    // face of a convex roof bending down beyond x = 2.
    h.add_triangle({-2, 1, -2}, {-2, 1, 2}, {0, 1, 2});
    const std::uint32_t left = h.add_triangle({-2, 1, -2}, {0, 1, 2}, {0, 1, -2});
    h.add_triangle({0, 1, -2}, {0, 1, 2}, {2, 1, 2});
    h.add_triangle({0, 1, -2}, {2, 1, 2}, {2, 1, -2});
    h.add_triangle({2, 1, -2}, {2, 1, 2}, {4, 0.5f, 0});
    // One float ulp below the floor, 2^-30 beside the shared edge: the segment to the light
    // crosses the floor's plane inside the right cell. And a sample exactly on the edge.
    const float below = std::nextafter(1.0f, 0.0f);
    const std::size_t beside = h.add_sample({-std::ldexp(1.0f, -30), below, 1.0f}, left);
    const std::size_t on_edge = h.add_sample({0.0f, 1.0f, 1.0f}, left);
    const Truths t = run_both(h);
    expect_robustly_lit(t, beside);
    expect_robustly_lit(t, on_edge);
  }
  // A wall on the floor: its faces rise above the floor's plane and shadow the floor behind it.
  auto h = make_hand_built_case(point_light({-6, 3, 0}));
  const std::uint32_t floor_cell = h.add_triangle({0, 1, -2}, {0, 1, 2}, {4, 1, 0});
  h.add_triangle({1, 1, -2}, {1, 1, 2}, {1, 3, 0});
  const std::size_t behind = h.add_sample({1.5f, std::nextafter(1.0f, 0.0f), 0.0f}, floor_cell);
  expect_robustly_shadowed(run_both(h), behind);
}

TEST(HardShadowOracles, NonCastersNeverShadow) {
  auto h = make_hand_built_case(point_light({0, 8, 0}));
  h.add_triangle({-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, testing::ground_mesh);
  expect_robustly_lit(run_both(h), h.add_ground_sample({0, 0, 0}));
}

TEST(HardShadowOracles, DeepInsideAndFarOutsideAreRobust) {
  for (const ShadowLight& light : {point_light({0, 8, 0}), directional_light({0, 1, 0})}) {
    auto h = make_hand_built_case(light);
    h.add_triangle({-2, 2, -2}, {2, 2, -2}, {0, 2, 2});
    const std::size_t inside = h.add_ground_sample({0, 0, 0});
    const std::size_t outside = h.add_ground_sample({6, 0, 0});
    const Truths t = run_both(h);
    expect_robustly_shadowed(t, inside);
    expect_robustly_lit(t, outside);
  }
}

TEST(HardShadowOracles, SamplesThatAreNotRegularAreNotCompared) {
  auto h = make_hand_built_case(point_light({0, 8, 0}));
  h.add_triangle({-2, 2, -2}, {2, 2, -2}, {0, 2, 2});
  h.add_ground_sample({0, 0, 0});
  h.add_ground_sample({0, 0, 0});
  h.samples.samples[0].sample_class = SampleClass::sky;
  h.samples.samples[1].sample_class = SampleClass::back_facing;
  const Truths t = run_both(h);
  for (const HardShadowTruth* truth : {&t.exact, &t.embree})
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(truth->shadowed[i], 0);
      EXPECT_EQ(truth->band[i], BandClass::not_compared);
    }
}

TEST(HardShadowOracles, RejectLightsWithoutHardShadows) {
  auto h = make_hand_built_case(point_light({0, 8, 0}));
  h.add_ground_sample({0, 0, 0});
  h.c.light->kind = ShadowLightKind::sun_disk;
  h.c.light->direction = {0, 1, 0};
  EXPECT_THROW(exact_hard_shadow_oracle_with_exponents(h.c, h.samples), InputError);
  EXPECT_THROW(embree_hard_shadow_oracle(h.c, h.samples), InputError);
  h.c.light.reset();
  EXPECT_THROW(exact_hard_shadow_oracle_with_exponents(h.c, h.samples), InputError);
}

// A sample at distance D = 2^-12 inside (or outside) the straight edge z = -1 of a blocker at
// y = 2, light straight above at y = 8. A move by delta along u lands the segment's crossing of
// y = 2 at z = p_z + delta u_z (1 - t), 1 - t = 6 / (8 - delta u_y): the answer flips first for
// u = (x, 1, -+1), once 6 delta / (8 - delta) > D.
class BandAroundAnEdge : public ::testing::TestWithParam<double> {};

bool flips(double delta, double distance) {
  return 6.0 * delta / (8.0 - delta) > distance;
}

TEST_P(BandAroundAnEdge, RobustExponentAgreesWithTheBandAtEveryEpsRel) {
  const double distance = 0x1p-12;
  const double side = GetParam();  // +1: inside the shadow, -1: outside
  const float z = float(-1.0 + side * distance);
  auto h = make_hand_built_case(point_light({0, 8, z}));
  h.add_triangle({-4, 2, -1}, {4, 2, -1}, {0, 2, 3});
  const std::size_t i = h.add_ground_sample({0, 0, z});
  const double scale = h.c.scale();
  ASSERT_EQ(scale, 8.0);

  int expected_exponent = band_min_exponent - 1;
  while (expected_exponent < band_max_exponent &&
         !flips(std::ldexp(scale, expected_exponent + 1), distance))
    ++expected_exponent;
  ASSERT_EQ(expected_exponent, -15);  // the configuration is what the comment says

  const HardShadowTruth base = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  EXPECT_EQ(base.shadowed[i], side > 0 ? 1 : 0);
  EXPECT_EQ(base.robust_exponent[i], expected_exponent);

  // Recompute the class at every power of two and at values in between: robust exactly when
  // no move length eps_rel S 2^-j >= 2^-24 S flips the answer.
  for (double eps_rel = 0x1p-24; eps_rel <= 0x1p-8; eps_rel *= std::sqrt(std::sqrt(2.0))) {
    h.c.parameters.eps_rel = eps_rel;
    const HardShadowTruth t = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
    bool robust = true;
    for (double delta = eps_rel * scale; delta >= std::ldexp(scale, -24); delta *= 0.5)
      robust = robust && !flips(delta, distance);
    EXPECT_EQ(t.band[i] != BandClass::ambiguous, robust) << "eps_rel " << eps_rel;
    EXPECT_EQ(t.robust_exponent[i], expected_exponent);  // independent of eps_rel
    const int e = int(std::floor(std::log2(eps_rel)));
    if (std::ldexp(1.0, e) == eps_rel && e <= band_max_exponent) {
      EXPECT_EQ(t.band[i] != BandClass::ambiguous, e <= base.robust_exponent[i]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(InsideAndOutside, BandAroundAnEdge, ::testing::Values(1.0, -1.0));

// On every sample the exact oracle calls robust, Embree's robust-mode rays give the same answer.
class RandomCaseAgreement : public ::testing::TestWithParam<int> {};

TEST_P(RandomCaseAgreement, ExactAndEmbreeAgreeOnRobustSamples) {
  const ShadowLight light = GetParam() == 0 ? point_light({1.5f, 10.0f, 0.75f})
                                            : directional_light({0.25f, 1.0f, -0.375f});
  // With samples at the shadow images of blocker vertices: the 14 moves alone called some of them
  // robust-lit where Embree sees the vertex (ThinWedgeApexIsAmbiguous); the cube does not.
  const auto h = testing::make_random_case(11 + std::uint64_t(GetParam()), 16, 2500, 0.75f, 4000,
                                           light, /*vertex_images=*/true);
  const Truths t = run_both(h);
  std::size_t robust = 0, shadowed = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    if (t.exact.band[i] == BandClass::ambiguous) continue;
    ++robust;
    shadowed += t.exact.shadowed[i];
    EXPECT_EQ(t.exact.shadowed[i], t.embree.shadowed[i]) << "robust sample " << i;
    EXPECT_EQ(t.exact.band[i] == BandClass::robust_shadowed, t.exact.shadowed[i] == 1);
  }
  // The case is a real test: most samples are robust, and a fair share of them is shadowed.
  EXPECT_GT(robust, h.samples.samples.size() / 2);
  EXPECT_GT(shadowed, robust / 10);
  EXPECT_LT(shadowed, robust * 9 / 10);
}

INSTANTIATE_TEST_SUITE_P(PointAndDirectional, RandomCaseAgreement, ::testing::Values(0, 1));

TEST(HardShadowOracles, ExactOracleIsTheSameForAnyThreadCount) {
  auto h = testing::make_random_case(5, 8, 1500, 0.75f, 3000, point_light({1.5f, 10.0f, 0.75f}));
  h.c.parameters.threads = 1;
  const HardShadowTruth one = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  h.c.parameters.threads = 0;
  const HardShadowTruth all = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  h.c.parameters.threads = 3;
  const HardShadowTruth three = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  for (const HardShadowTruth* other : {&all, &three}) {
    EXPECT_EQ(one.shadowed, other->shadowed);
    EXPECT_EQ(one.band, other->band);
    EXPECT_EQ(one.robust_exponent, other->robust_exponent);
  }
}

}  // namespace
}  // namespace shadowcts
