// Found by the watertightness fuzzer: a sample inside a closed caster mesh is shadowed (its
// segment must leave the solid), but only through faces turned towards the light — the faces the
// papers' front-face culling drops. ptsv and psv leaked there; both now keep those faces whenever
// a sample (or the point light) may be inside the solid.
#include "reference/closed_mesh_culling.h"

#include <gtest/gtest.h>

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
