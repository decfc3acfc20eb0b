// Found by the watertightness fuzzer: a sample inside a closed caster mesh is shadowed (its
// segment must leave the solid), but only through faces turned towards the light — the faces the
// papers' front-face culling drops. ptsv and psv leaked there; both now keep those faces whenever
// a sample (or the point light) may be inside the solid.
#include "reference/closed_mesh_culling.h"

#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"

namespace shadowcts {
namespace {

// A closed octahedron (radius 1, outward winding) around the origin, a non-caster floor far
// below as the sample's receiver, one sample at the centre seen by a 1x1 camera.
struct InsideSolid {
  Case c;
  ViewSamples samples;
};

InsideSolid sample_inside_closed_octahedron(ShadowLight light) {
  InsideSolid s;
  Case& c = s.c;
  c.name = "test.inside_closed_octahedron";
  c.source = "test";
  c.meshes = {{"floor", false, false}, {"octahedron", true, true}};
  c.triangles.push_back({{-8, -5, -8}, {8, -5, -8}, {0, -5, 8}, 0});
  const glm::vec3 px{1, 0, 0}, nx{-1, 0, 0}, py{0, 1, 0}, ny{0, -1, 0}, pz{0, 0, 1}, nz{0, 0, -1};
  for (const auto& [a, b, d] : {std::tuple{px, py, pz},
                                {py, nx, pz},
                                {nx, ny, pz},
                                {ny, px, pz},
                                {py, px, nz},
                                {nx, py, nz},
                                {ny, nx, nz},
                                {px, ny, nz}})
    c.triangles.push_back({a, b, d, 1});
  c.light = light;
  c.camera.position = {0.25f, 0.5f, -10.0f};
  c.camera.target = {0, 0, 0};
  c.camera.width = c.camera.height = 1;
  validate(c);
  s.samples.width = s.samples.height = 1;
  ViewSample v;
  v.position = {0, 0, 0};
  v.normal = {0, 0, -1};
  v.receiver = 0;
  v.sample_class = SampleClass::regular;
  s.samples.samples = {v};
  return s;
}

TEST(ClosedMeshCulling, NotWhenASampleOrThePointLightIsInsideTheBox) {
  ShadowLight directional;
  directional.kind = ShadowLightKind::directional;
  directional.direction = {0, 0.6f, 0.8f};
  InsideSolid s = sample_inside_closed_octahedron(directional);
  EXPECT_EQ(meshes_safe_for_face_culling(s.c, s.samples), (std::vector<bool>{false, false}));
  s.samples.samples[0].position = {3, 3, 3};  // outside the box
  EXPECT_EQ(meshes_safe_for_face_culling(s.c, s.samples), (std::vector<bool>{false, true}));
  ShadowLight point;
  point.position = {0.5f, 0, 0};  // inside the solid
  s.c.light = point;
  EXPECT_EQ(meshes_safe_for_face_culling(s.c, s.samples), (std::vector<bool>{false, false}));
}

// Closed boxes at random, samples at random and on the boxes' faces, edges and corners, each
// sample's receiver a triangle of any mesh (its own box's or another's): the culling must match
// its definition, tested box by box and sample by sample.
TEST(ClosedMeshCulling, MatchesTheDefinitionOnSamplesOnBoxFacesAndCorners) {
  std::mt19937 random(7);
  const auto coordinate = [&] { return float(int(random() % 41) - 20) * 0.25f; };
  for (int round = 0; round < 40; ++round) {
    Case c;
    c.name = "test.boxes";
    c.source = "test";
    std::vector<glm::vec3> lo, hi;
    const int boxes = 1 + int(random() % 12);
    for (int b = 0; b < boxes; ++b) {
      glm::vec3 a{coordinate(), coordinate(), coordinate()};
      glm::vec3 d{coordinate(), coordinate(), coordinate()};
      if (a.x == d.x) d.x += 0.5f;
      if (a.y == d.y) d.y += 0.5f;
      if (a.z == d.z) d.z += 0.5f;
      lo.push_back(glm::min(a, d));
      hi.push_back(glm::max(a, d));
      c.meshes.push_back({"box", random() % 4 != 0, random() % 5 != 0});
      const auto corner = [&](int k) {
        return glm::vec3((k & 1) ? hi[b].x : lo[b].x, (k & 2) ? hi[b].y : lo[b].y,
                         (k & 4) ? hi[b].z : lo[b].z);
      };
      // Two triangles per face of the cube (windings do not matter here).
      for (const auto& [p, q, r, t] : {std::tuple{0, 1, 3, 2},
                                       {4, 5, 7, 6},
                                       {0, 1, 5, 4},
                                       {2, 3, 7, 6},
                                       {0, 2, 6, 4},
                                       {1, 3, 7, 5}}) {
        c.triangles.push_back({corner(p), corner(q), corner(r), std::uint32_t(b)});
        c.triangles.push_back({corner(p), corner(r), corner(t), std::uint32_t(b)});
      }
    }
    ShadowLight light;
    light.position = {coordinate(), coordinate(), coordinate()};
    if (random() % 2 == 0) {
      light.kind = ShadowLightKind::directional;
      light.direction = {0, 0.6f, 0.8f};
    }
    c.light = light;
    ViewSamples samples;
    const int count = int(random() % 60);
    for (int i = 0; i < count; ++i) {
      ViewSample v;
      const int b = int(random() % std::uint32_t(boxes));
      const int snap = int(random() % 3);  // 0: anywhere, 1: a face, edge or corner of box b
      v.position = {coordinate(), coordinate(), coordinate()};
      if (snap == 1)
        for (int k = 0; k < 3; ++k)
          if (random() % 2 == 0) v.position[k] = random() % 2 == 0 ? lo[b][k] : hi[b][k];
      if (snap == 2) v.position = random() % 2 == 0 ? hi[b] : lo[b];
      v.receiver = std::uint32_t(random() % c.triangles.size());
      v.sample_class = random() % 6 == 0 ? SampleClass::back_facing : SampleClass::regular;
      samples.samples.push_back(v);
    }
    std::vector<bool> expected(c.meshes.size());
    for (int b = 0; b < boxes; ++b) {
      const auto in_box = [&](const glm::vec3& p) {
        return glm::all(glm::greaterThanEqual(p, lo[b])) && glm::all(glm::lessThanEqual(p, hi[b]));
      };
      bool safe = c.meshes[b].closed && c.meshes[b].caster;
      if (light.kind == ShadowLightKind::point && in_box(light.position)) safe = false;
      for (const ViewSample& v : samples.samples)
        if (v.sample_class == SampleClass::regular && in_box(v.position)) safe = false;
      expected[b] = safe;
    }
    EXPECT_EQ(meshes_safe_for_face_culling(c, samples), expected) << "round " << round;
  }
}

// Boxes near the largest floats, whose spread overflows: a sample in the far box is still found.
TEST(ClosedMeshCulling, FindsSamplesInBoxesWhoseSpreadOverflows) {
  Case c;
  c.name = "test.huge_boxes";
  c.source = "test";
  c.meshes = {{"left", true, true}, {"right", true, true}};
  const float far = 3e38f, near = 1e38f;
  for (const float sign : {-1.0f, 1.0f}) {
    const std::uint32_t mesh = sign < 0.0f ? 0 : 1;
    const glm::vec3 a{sign * near, -1.0f, -1.0f}, b{sign * far, 1.0f, 1.0f};
    c.triangles.push_back({a, {b.x, a.y, a.z}, {a.x, b.y, b.z}, mesh});
    c.triangles.push_back({b, {a.x, b.y, b.z}, {b.x, a.y, b.z}, mesh});
  }
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {0, 1, 0};
  c.light = light;
  ViewSamples samples;
  for (const float x : {2e38f, 3e38f, 1e38f}) {
    ViewSample v;
    v.position = {x, 0.5f, 0.0f};
    v.receiver = 0;  // the left mesh's: not its own box
    v.sample_class = SampleClass::regular;
    samples.samples = {v};
    EXPECT_EQ(meshes_safe_for_face_culling(c, samples), (std::vector<bool>{true, false})) << x;
  }
}

TEST(ClosedMeshCulling, PlaneBasedAlgorithmsShadowASampleInsideAClosedCaster) {
  for (const glm::vec3 direction : {glm::vec3{0, 0.6f, 0.8f}, glm::vec3{-0.48f, 0.6f, 0.64f}}) {
    ShadowLight light;
    light.kind = ShadowLightKind::directional;
    light.direction = direction;
    const InsideSolid s = sample_inside_closed_octahedron(light);
    const HardShadowTruth truth = exact_hard_shadow_oracle(s.c, s.samples);
    ASSERT_EQ(truth.band[0], BandClass::robust_shadowed);
    for (const char* id : {"ptsv", "psv"}) {
      const Algorithm* algorithm = builtin_registry().find(id, "reference");
      ASSERT_NE(algorithm, nullptr);
      for (const std::string& variant : algorithm->info().variants) {
        ASSERT_FALSE(algorithm->unsupported_reason(s.c, s.samples, variant)) << id << variant;
        const AlgorithmOutput out = algorithm->run(s.c, s.samples, variant);
        EXPECT_EQ(compare_hard_shadows(out.shadowed, truth).verdict, Verdict::pass)
            << id << ":" << variant;
      }
    }
  }
}

}  // namespace
}  // namespace shadowcts
