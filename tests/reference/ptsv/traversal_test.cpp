// Traversal: trivially accepted nodes really lie inside the volume, rejected ones outside; every
// variant and every two-pass job level gives the mask of testing every sample against every
// volume; the counters are deterministic.
#include "reference/ptsv/traversal.h"

#include <gtest/gtest.h>

#include "big_shadow_case.h"
#include "ptsv_test_support.h"
#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/two_pass.h"
#include "shadowcts/errors.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts::ptsv {
namespace {

// Independent of the plane code: does the segment from x to the light (ray towards it) meet the
// triangle's interior, computed by intersecting the triangle's plane in double?
bool in_shadow_of(const Triangle& t, const ShadowLight& light, const glm::dvec3& x) {
  const glm::dvec3 a(t.v0), b(t.v1), c(t.v2);
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const glm::dvec3 dir = light.kind == ShadowLightKind::point ? glm::dvec3(light.position) - x
                                                              : glm::dvec3(light.direction);
  const double denom = glm::dot(n, dir);
  if (denom == 0.0) return false;
  const double s = glm::dot(n, a - x) / denom;
  if (s < 0.0 || (light.kind == ShadowLightKind::point && s > 1.0)) return false;
  const glm::dvec3 hit = x + s * dir;
  const double u = glm::dot(glm::cross(b - a, hit - a), n),
               v = glm::dot(glm::cross(c - b, hit - b), n),
               w = glm::dot(glm::cross(a - c, hit - c), n);
  return u >= 0.0 && v >= 0.0 && w >= 0.0;
}

struct Scene {
  Case c;
  ViewSamples samples;
  ViewFrame frame;
  ClusterKeyLayout layout;
  ClusterKeys keys;
  std::vector<ShadowVolume> volumes;
  double bound = 0.0;
  explicit Scene(bool directional) {
    c = ptsv_test::big_shadow_case(directional);
    samples = generate_view_samples(c);
    frame = make_view_frame(c.camera, samples.width, samples.height);
    layout = make_cluster_key_layout(c.camera, samples.width, samples.height).layout;
    keys = assign_cluster_keys(layout, frame, samples, true);
    bound = 20.0;
    SetupCounts counts;
    SetupOptions options;
    options.extra_planes = true;
    volumes =
        set_up_shadow_volumes(c, std::vector<bool>(c.meshes.size(), false), options, bound, counts);
  }
};

TEST(Traversal, TriviallyAcceptedNodesLieInsideTheVolumeAndRejectedOnesOutside) {
  for (bool directional : {false, true}) {
    const Scene s(directional);
    ASSERT_TRUE(s.keys.problem.empty()) << s.keys.problem;
    const ReceiverRule rule(s.c, s.samples);
    const ClusterHierarchy h(s.layout, s.keys.key, s.samples, rule.reject_reach());
    const NodeTolerances tolerances = NodeTolerances::for_bounds(100.0, s.bound);
    const ShadowVolume& caster = s.volumes.back();  // the big triangle
    ASSERT_EQ(caster.triangle, 2u);
    const Triangle& tri = s.c.triangles[2];
    int accepted = 0, rejected = 0;
    for (NodeBounds bounds : {NodeBounds::implicit_cells, NodeBounds::explicit_boxes})
      for (int l = 1; l <= h.leaf_level(); ++l)
        for (std::uint32_t node : h.level(l).index) {
          TraversalCounters counters;
          std::array<glm::dvec3, 8> corners;
          if (bounds == NodeBounds::implicit_cells) {
            corners = cell_corners(s.frame, implicit_node_cell(s.layout, l, node));
          } else {
            const WorldBox& box = h.bounds(l, node);
            for (int i = 0; i < 8; ++i)
              corners[std::size_t(i)] = {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                                         i & 4 ? box.hi.z : box.lo.z};
          }
          const auto reach = [&] { return h.level(l).reject_reach[std::size_t(h.find(l, node))]; };
          const NodeVerdict verdict = bounds == NodeBounds::implicit_cells
                                          ? classify_node(caster, corners, tolerances,
                                                          CullingPlanes::extra, counters, reach)
                                          : classify_node(caster, h.bounds(l, node), tolerances,
                                                          CullingPlanes::extra, counters, reach);
          if (verdict == NodeVerdict::refine) continue;
          // The node's samples: those whose key has this prefix.
          for (std::size_t i = 0; i < s.keys.key.size(); ++i) {
            if (s.keys.key[i] == no_key) continue;
            if ((std::uint64_t(s.keys.key[i]) >> (5 * (h.leaf_level() - l))) != node) continue;
            const glm::dvec3 p(s.samples.samples[i].position);
            EXPECT_EQ(in_shadow_of(tri, *s.c.light, p), verdict == NodeVerdict::accept)
                << "level " << l << " node " << node << " sample " << i;
          }
          if (verdict == NodeVerdict::accept) {
            ++accepted;
            for (const glm::dvec3& corner : corners)
              EXPECT_TRUE(in_shadow_of(tri, *s.c.light, corner));
          } else {
            ++rejected;
          }
        }
    EXPECT_GT(accepted, 10) << (directional ? "directional" : "point");
    EXPECT_GT(rejected, 10);
  }
}

// Every sample against every volume, under the receiver half-space rule: the mask every variant
// must reproduce.
std::vector<std::uint8_t> brute_force_mask(const Scene& s) {
  const ReceiverRule rule(s.c, s.samples);
  std::vector<std::uint8_t> mask(s.samples.samples.size(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const ViewSample& sample = s.samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    for (const ShadowVolume& v : s.volumes)
      if (sample_in_volume(v, sample) && rule.caster_counts(v, sample)) mask[i] = 1;
  }
  return mask;
}

TEST(Traversal, EveryVariantAndJobLevelGivesTheBruteForceMask) {
  for (bool directional : {false, true}) {
    const Scene s(directional);
    const std::vector<std::uint8_t> expected = brute_force_mask(s);
    std::size_t shadowed = 0;
    for (std::uint8_t m : expected) shadowed += m;
    ASSERT_GT(shadowed, 500u);
    const auto algorithm = make_ptsv();
    for (const std::string& variant : algorithm->info().variants) {
      const AlgorithmOutput out = algorithm->run(s.c, s.samples, variant);
      EXPECT_EQ(out.shadowed, expected) << variant;
      EXPECT_EQ(algorithm->run(s.c, s.samples, variant).counters, out.counters) << variant;
      EXPECT_GT(ptsv_test::counter(out, "trivial_accepts"), 0u) << variant;
    }
    for (int job_level = 1; job_level <= s.layout.mask_levels(); ++job_level) {
      const ReceiverRule rule(s.c, s.samples);
      ClusterHierarchy h(s.layout, s.keys.key, s.samples, rule.reject_reach());
      std::vector<std::uint8_t> mask(s.samples.samples.size(), 0);
      TraversalCounters counters;
      ClusterTraversal traversal(h, s.frame, s.samples, rule, NodeBounds::explicit_boxes, true,
                                 NodeTolerances::for_bounds(s.bound, s.bound), mask, counters);
      traverse_two_pass(traversal, s.volumes, job_level, counters);
      traversal.mark_trivially_accepted(s.keys.key);
      EXPECT_EQ(mask, expected) << "job level " << job_level;
      EXPECT_EQ(counters.first_pass_jobs, counters.second_pass_jobs);
      EXPECT_GT(counters.first_pass_jobs, 0u);
    }
  }
}

TEST(Traversal, KeyLayoutOverflowIsRefusedNotWrapped) {
  Case c = ptsv_test::big_shadow_case(false);
  c.camera.near_plane = 1e-3f;
  c.camera.far_plane = 1e4f;
  ViewSamples samples;
  samples.width = 1;
  samples.height = 262144;  // 32768 tile rows: 15 y bits and very thin depth slices
  samples.samples.resize(samples.height);
  for (std::uint32_t y = 0; y < samples.height; ++y) samples.samples[y].pixel_y = y;
  const auto algorithm = make_ptsv();
  for (const std::string variant : {"twopass", "implicit", "explicit+planes"}) {
    const auto why = algorithm->unsupported_reason(c, samples, variant);
    ASSERT_TRUE(why.has_value()) << variant;
    EXPECT_NE(why->find("bits"), std::string::npos) << *why;
    EXPECT_THROW(algorithm->run(c, samples, variant), InputError) << variant;
  }
}

// fuzz_watertight-8cd4243f0fc51fa8: a T-junction (a vertex of one caster in the middle of the
// other's edge) and a sample whose segment passes exactly through the edge piece both cover, so
// both triangles block it. Their edge planes lie on one line but are crossed from different
// vertices, so they round differently, and the sample fell outside both: every variant leaked.
// Within rounding of a plane the sample test now decides by the exact orientation sign.
TEST(Traversal, NoLeakThroughTheRoundedPlanesOfATJunction) {
  Case c;
  c.name = "t_junction";
  c.source = "traversal_test.cpp";
  c.meshes = {Mesh{"receiver", false, false}, Mesh{"surface", false, true}};
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {24.0f, -24.0f, -15.0f};
  c.light = light;
  c.camera.position = {9.393692016601562f, -15.036345481872559f, -11.059608459472656f};
  c.camera.target = {-63.095703125f, 29.44921875f, 8.49609375f};
  c.camera.near_plane = 0.00015200885536614805f;
  c.camera.far_plane = 152008.859375f;
  c.camera.width = c.camera.height = 1;
  // The receiver holds the sample in its plane (x = the sample's x), the casters on its light's
  // side, so the receiver half-space rule keeps them.
  constexpr float receiver_x = -0x1.fcc4p+6f;
  c.triangles = {{{receiver_x, 60, 20}, {receiver_x, 70, 20}, {receiver_x, 65, 30}, 0},
                 {{-0x1.8ep+2f, -0x1.72p+2f, -0x1.7p+2f},
                  {-0x1.5p+2f, -0x1.68p+2f, -0x1.b8p+2f},
                  {-0x1.9p+2f, -0x1.76p+2f, -0x1.f4p+2f},
                  1},
                 {{-0x1.8ep+2f, -0x1.72p+2f, -0x1.7p+2f},
                  {-0x1.8fcp+2f, -0x1.758p+2f, -0x1.e38p+2f},  // on the first one's edge
                  {-0x1.dp+2f, -0x1.98p+2f, -0x1.b8p+2f},
                  1}};
  ViewSamples samples;
  samples.width = samples.height = 1;
  ViewSample sample;
  sample.position = {-0x1.fcc4p+6f, 0x1.0b98p+6f, 0x1.8cep+4f};
  sample.normal = {1, 0, 0};
  sample.receiver = 0;
  sample.sample_class = SampleClass::regular;  // re-derived below
  samples.samples = {sample};
  validate(c);
  classify_samples(c, samples, c.name);
  ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  ASSERT_EQ(truth.band[0], BandClass::robust_shadowed);
  const auto algorithm = make_ptsv();
  for (const std::string& variant : algorithm->info().variants)
    EXPECT_EQ(algorithm->run(c, samples, variant).shadowed[0], 1) << variant;
}

}  // namespace
}  // namespace shadowcts::ptsv
