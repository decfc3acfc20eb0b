// The receiver half-space rule (DESIGN.md, "Cases and ground truth") in every variant of `metric`
// and `bruteforce` and every backend of them that runs here (the `cuda` backend without a device
// must say so): hand-built cases whose answers follow from exact constructions. Each case also
// asserts, with the exact segment/triangle predicate, that it is a trap: without the rule the
// samples expected lit would be shadowed by a coplanar neighbour or the next face of the mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "hand_built_case.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/registry.h"

namespace shadowcts {
namespace {

using testing::HandBuiltCase;

struct RuleCase {
  HandBuiltCase h;
  std::vector<std::uint8_t> expected;  // per sample
  // Samples expected lit whose segment (ray) some caster other than the receiver meets.
  std::size_t traps = 0;
};

constexpr float floor_height = 1.0f;
// The float just below 1: one ulp under the floor's plane.
const float below_floor = std::nextafter(floor_height, 0.0f);

// A floor of 2 x 4 x 4 coplanar caster triangles on [-4, 4]^2 at y = 1 (cells of 2, diagonals
// from (x0, z0) to (x0 + 2, z0 + 2)). Returns the index of the first triangle.
std::uint32_t add_tessellated_floor(HandBuiltCase& h) {
  const std::uint32_t first = std::uint32_t(h.c.triangles.size());
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const float x0 = -4.0f + 2.0f * float(i), z0 = -4.0f + 2.0f * float(k);
      const glm::vec3 a{x0, floor_height, z0}, b{x0 + 2, floor_height, z0},
          d{x0 + 2, floor_height, z0 + 2}, e{x0, floor_height, z0 + 2};
      // Wound so that the normal points up (towards +y).
      h.add_triangle(a, d, b, testing::caster_ground_mesh);
      h.add_triangle(a, e, d, testing::caster_ground_mesh);
    }
  return first;
}

// The floor triangles that hold (x, z) (one, or the two beside a shared edge).
std::vector<std::uint32_t> floor_triangles_at(std::uint32_t first, float x, float z) {
  std::vector<std::uint32_t> found;
  for (std::uint32_t t = 0; t < 32; ++t) {
    const int i = int(t / 2) / 4, k = int(t / 2) % 4;
    const float fx = x - (-4.0f + 2.0f * float(i)), fz = z - (-4.0f + 2.0f * float(k));
    if (fx < 0 || fx > 2 || fz < 0 || fz > 2) continue;
    if (t % 2 == 0 ? fx >= fz : fz >= fx) found.push_back(first + t);
  }
  return found;
}

// Does some caster other than the sample's receiver meet its segment, by the exact predicate
// (the old answer, without the rule)?
bool met_by_another_caster(const HandBuiltCase& h, std::size_t sample) {
  const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
  const ViewSample& s = h.samples.samples[sample];
  for (std::size_t t = 0; t < h.c.triangles.size(); ++t) {
    if (t == s.receiver || !casts_shadow(h.c, t)) continue;
    if (predicate.blocks(h.c.triangles[t], MovedPoint{glm::dvec3(s.position), 0.0, {0, 0, 0}}))
      return true;
  }
  return false;
}

void count_traps(RuleCase& rule) {
  for (std::size_t i = 0; i < rule.expected.size(); ++i)
    if (rule.expected[i] == 0 && met_by_another_caster(rule.h, i)) ++rule.traps;
}

// Samples beside the floor's shared edges (on them, and 2^-23 inside a triangle), each once for
// every triangle that holds it, on the floor's plane and one ulp below it.
void add_floor_edge_samples(HandBuiltCase& h, std::uint32_t first,
                            std::vector<std::uint8_t>& expected, float lit_x_min = -INFINITY) {
  std::vector<glm::vec2> points;
  for (const float line : {-2.0f, 0.0f, 2.0f})
    for (float along = -3.75f; along < 4.0f; along += 0.5f) {
      points.push_back({line, along});  // x = line
      points.push_back({along, line});  // z = line
    }
  for (float t = 0.125f; t < 2.0f; t += 0.375f) points.push_back({-2.0f + t, -2.0f + t});
  for (float t = 0.125f; t < 2.0f; t += 0.375f) points.push_back({t, 2.0f + t});
  const float inside = 0x1p-23f;
  for (const glm::vec2& q : points)
    for (const glm::vec2& offset :
         {glm::vec2(0.0f), glm::vec2(inside, 0.0f), glm::vec2(-inside, 0.0f),
          glm::vec2(0.0f, inside), glm::vec2(0.0f, -inside)}) {
      const glm::vec2 p = q + offset;
      if (p.x < lit_x_min) continue;
      for (const std::uint32_t r : floor_triangles_at(first, p.x, p.y))
        for (const float y : {floor_height, below_floor}) {
          h.add_sample({p.x, y, p.y}, r);
          expected.push_back(0);
        }
    }
}

// (1), (4): a tessellated floor lit from a low light; samples beside its shared edges.
RuleCase tessellated_floor(bool directional) {
  RuleCase rule{
      testing::make_hand_built_case(directional ? testing::directional_light({1.0f, 0.5f, 0.25f})
                                                : testing::point_light({5.0f, 2.5f, 1.25f})),
      {},
      0};
  const std::uint32_t first = add_tessellated_floor(rule.h);
  add_floor_edge_samples(rule.h, first, rule.expected);
  count_traps(rule);
  return rule;
}

// (2): a closed convex mesh, an octahedron with every face split into four coplanar triangles;
// samples on its lit faces beside every edge, rounded to float (either side of the face's plane)
// and, on the edges, moved one ulp into the solid.
RuleCase convex_mesh() {
  RuleCase rule{testing::make_hand_built_case(testing::point_light({3.0f, 12.0f, 2.5f})), {}, 0};
  HandBuiltCase& h = rule.h;
  h.c.meshes.push_back(Mesh{"octahedron", true, true});
  const std::uint32_t mesh = std::uint32_t(h.c.meshes.size() - 1);
  const glm::vec3 centre{0, 4, 0};
  const glm::vec3 corner[6] = {{2, 4, 0}, {-2, 4, 0}, {0, 6, 0}, {0, 2, 0}, {0, 4, 2}, {0, 4, -2}};
  std::vector<std::uint32_t> faces;
  for (int sx : {0, 1})
    for (int sy : {2, 3})
      for (int sz : {4, 5}) {
        glm::vec3 a = corner[sx], b = corner[sy], d = corner[sz];
        if (glm::dot(glm::cross(b - a, d - a), a - centre) < 0) std::swap(b, d);  // outwards
        const glm::vec3 ab = 0.5f * (a + b), bd = 0.5f * (b + d), da = 0.5f * (d + a);
        for (const auto& [p, q, s] : {std::tuple{a, ab, da}, std::tuple{ab, b, bd},
                                      std::tuple{da, bd, d}, std::tuple{ab, bd, da}})
          faces.push_back(h.add_triangle(p, q, s, mesh));
      }
  const glm::dvec3 light(h.c.light->position);
  for (const std::uint32_t f : faces) {
    const Triangle t = h.c.triangles[f];
    const glm::vec3 normal = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
    if (glm::dot(glm::dvec3(normal), light - glm::dvec3(t.v0)) <= 0.5) continue;  // clearly lit
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int e = 0; e < 3; ++e) {
      const glm::vec3 p = v[e], q = v[(e + 1) % 3], s = v[(e + 2) % 3];
      for (const float along : {0.125f, 0.375f, 0.5f, 0.8125f})
        for (const float off : {0.0f, 0x1p-22f, 0x1p-18f}) {
          glm::vec3 x = p + along * (q - p) + off * (s - p);  // rounded to float
          if (off == 0.0f) x.y = std::nextafter(x.y, 0.0f);   // into the solid: below the face
          h.add_sample(x, f);
          h.samples.samples.back().normal = normal;
          rule.expected.push_back(0);
        }
    }
  }
  count_traps(rule);
  return rule;
}

// (3): a wall standing on the tessellated floor (its foot in the floor's plane) shadows the floor
// behind it, also one ulp below the floor's plane and next to its foot; the floor in front of it
// stays lit beside its shared edges.
RuleCase wall_on_floor(bool directional) {
  RuleCase rule{
      testing::make_hand_built_case(directional ? testing::directional_light({1.0f, 0.25f, 0.0625f})
                                                : testing::point_light({4.5f, 3.5f, 0.25f})),
      {},
      0};
  HandBuiltCase& h = rule.h;
  const std::uint32_t first = add_tessellated_floor(h);
  const float wall_x = 0.5f;
  h.add_triangle({wall_x, floor_height, -2}, {wall_x, floor_height, 2}, {wall_x, 3, 2});
  h.add_triangle({wall_x, floor_height, -2}, {wall_x, 3, 2}, {wall_x, 3, -2});
  // Behind the wall (x < 0.5): every segment crosses the wall's plane at a height between
  // 1 + 2^-19 and 2 and at |z| < 1.5, well inside the wall.
  for (const float distance : {0x1p-16f, 0x1p-10f, 0.25f, 1.0f, 2.0f})
    for (const float z : {-1.0f, -0.3125f, 0.0f, 0.625f, 1.0f})
      for (const float y : {floor_height, below_floor}) {
        const float x = wall_x - distance;
        for (const std::uint32_t r : floor_triangles_at(first, x, z)) {
          h.add_sample({x, y, z}, r);
          rule.expected.push_back(1);
        }
      }
  add_floor_edge_samples(h, first, rule.expected, wall_x + 0x1p-10f);
  count_traps(rule);
  return rule;
}

// The same case with every coordinate multiplied by 2^exponent (exact in float for these cases):
// the rule's orientations and the float tests must hold far from unit scale.
RuleCase scaled(RuleCase rule, int exponent) {
  const auto scale = [exponent](glm::vec3& v) {
    v = glm::vec3(std::ldexp(v.x, exponent), std::ldexp(v.y, exponent), std::ldexp(v.z, exponent));
  };
  for (Triangle& t : rule.h.c.triangles) {
    scale(t.v0);
    scale(t.v1);
    scale(t.v2);
  }
  for (ViewSample& s : rule.h.samples.samples) scale(s.position);
  if (rule.h.c.light->kind == ShadowLightKind::point) scale(rule.h.c.light->position);
  scale(rule.h.c.camera.position);
  scale(rule.h.c.camera.target);
  return rule;
}

// Every (algorithm, backend, variant) of metric and bruteforce gives the expected answers; the
// cuda backend without a device reports "no CUDA device" instead.
void expect_every_variant_follows_the_rule(const RuleCase& rule, const std::string& what) {
  std::size_t runs = 0;
  for (const auto& algorithm : builtin_registry().algorithms()) {
    const AlgorithmInfo& info = algorithm->info();
    if (info.id != "metric" && info.id != "bruteforce") continue;
    for (const std::string& variant : info.variants) {
      const std::string name = info.id + "/" + info.backend + ":" + variant + " on " + what;
      if (const auto reason = algorithm->unsupported_reason(rule.h.c, rule.h.samples, variant)) {
        EXPECT_EQ(info.backend, "cuda") << name << ": " << *reason;
        EXPECT_EQ(reason->rfind("no CUDA device", 0), 0u) << name << ": " << *reason;
        continue;
      }
      const AlgorithmOutput output = algorithm->run(rule.h.c, rule.h.samples, variant);
      ASSERT_EQ(output.shadowed.size(), rule.expected.size()) << name;
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < rule.expected.size(); ++i)
        if (output.shadowed[i] != rule.expected[i] && ++wrong <= 5) {
          const ViewSample& s = rule.h.samples.samples[i];
          ADD_FAILURE() << name << ": sample " << i << " at (" << s.position.x << ", "
                        << s.position.y << ", " << s.position.z << ") receiver " << s.receiver
                        << " shadowed " << int(output.shadowed[i]) << ", expected "
                        << int(rule.expected[i]);
        }
      EXPECT_EQ(wrong, 0u) << name << ": wrong answers of " << rule.expected.size();
      ++runs;
    }
  }
  // bruteforce/reference, bruteforce/cuda-emu and the four metric variants at least.
  EXPECT_GE(runs, 6u) << what;
}

TEST(ReceiverHalfSpaceRule, TessellatedFloorOneUlpBelowItsPlaneIsLit) {
  const RuleCase rule = tessellated_floor(false);
  EXPECT_GT(rule.traps, rule.expected.size() / 8);
  expect_every_variant_follows_the_rule(rule, "tessellated floor, point light");
}

TEST(ReceiverHalfSpaceRule, TessellatedFloorUnderADirectionalLightIsLit) {
  const RuleCase rule = tessellated_floor(true);
  EXPECT_GT(rule.traps, rule.expected.size() / 8);
  expect_every_variant_follows_the_rule(rule, "tessellated floor, directional light");
}

TEST(ReceiverHalfSpaceRule, ConvexClosedMeshBesideItsEdgesIsLit) {
  const RuleCase rule = convex_mesh();
  EXPECT_GT(rule.traps, 10u);
  expect_every_variant_follows_the_rule(rule, "convex closed mesh");
}

TEST(ReceiverHalfSpaceRule, WallStandingOnTheFloorShadowsItsFoot) {
  for (const bool directional : {false, true}) {
    const RuleCase rule = wall_on_floor(directional);
    EXPECT_GT(rule.traps, 0u);
    expect_every_variant_follows_the_rule(
        rule, directional ? "wall on floor, directional light" : "wall on floor, point light");
  }
}

TEST(ReceiverHalfSpaceRule, HoldsAtScales2ToTheMinus60And60) {
  for (const int exponent : {-60, 60})
    for (const bool directional : {false, true}) {
      const std::string at = " at scale 2^" + std::to_string(exponent);
      expect_every_variant_follows_the_rule(scaled(tessellated_floor(directional), exponent),
                                            (directional ? "directional floor" : "floor") + at);
      expect_every_variant_follows_the_rule(scaled(wall_on_floor(directional), exponent),
                                            (directional ? "directional wall" : "wall") + at);
    }
  expect_every_variant_follows_the_rule(scaled(convex_mesh(), -60), "convex mesh at 2^-60");
  expect_every_variant_follows_the_rule(scaled(convex_mesh(), 60), "convex mesh at 2^60");
}

}  // namespace
}  // namespace shadowcts
