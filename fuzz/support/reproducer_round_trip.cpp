// Checks that a reproducer replays bit for bit: writes one for a small case with two meshes (a
// non-caster receiver and a closed caster box), a directional light and explicit samples, loads
// it the way `shadowcts run --case` does, and compares triangles, mesh flags, light, camera and
// samples exactly. Exit code 0 on success; run by fuzz/run_ci.sh before the fuzzers.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "fixtures/fuzz/sample_case.h"
#include "fixtures/fuzz/stable_direction.h"
#include "runner/case_reproducer.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"

namespace {

int failures = 0;

void expect(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "reproducer round trip: %s differs\n", what);
    ++failures;
  }
}

}  // namespace

int main() {
  using namespace shadowcts;
  fuzzing::SampleCase s;
  s.c.name = "round_trip";
  s.c.source = "reproducer_round_trip";
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = fuzzing::manifest_stable_direction({0.3f, 1.0f, -0.7f});
  s.c.light = light;
  s.begin_mesh("receiver", false, false);
  const std::uint32_t receiver = s.add_triangle({-4, 0, -4}, {4, 0, -4}, {0, 0, 4});
  s.begin_mesh("box", true);
  // A unit cube with outward winding, offset by values that are not dyadic.
  const glm::vec3 o(0.1f, 1.3f, -0.7f);
  const glm::vec3 p[8] = {o + glm::vec3(0, 0, 0), o + glm::vec3(1, 0, 0), o + glm::vec3(1, 1, 0),
                          o + glm::vec3(0, 1, 0), o + glm::vec3(0, 0, 1), o + glm::vec3(1, 0, 1),
                          o + glm::vec3(1, 1, 1), o + glm::vec3(0, 1, 1)};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    s.add_triangle(p[f[0]], p[f[1]], p[f[2]]);
    s.add_triangle(p[f[0]], p[f[2]], p[f[3]]);
  }
  s.add_sample({0.5f, 0.0f, 0.25f}, receiver);
  s.add_sample({1.0f / 3.0f, 0.0f, -0.1f}, receiver);
  s.add_sample({0.6f, 1.3f, -0.2f}, 2);  // on the box's bottom: faces down, so back-facing
  s.finish();

  const std::string folder =
      (std::filesystem::temp_directory_path() / "shadowcts_reproducer_round_trip").string();
  std::filesystem::remove_all(folder);
  const std::string manifest = write_reproducer(folder, s.c, s.samples);
  Case c = load_case_manifest(manifest);
  ViewSamples samples = read_gbuffer_exr(c.gbuffer_path);
  classify_samples(c, samples, c.gbuffer_path);

  expect(c.triangles.size() == s.c.triangles.size(), "triangle count");
  for (std::size_t i = 0; i < std::min(c.triangles.size(), s.c.triangles.size()); ++i) {
    const Triangle &a = c.triangles[i], &b = s.c.triangles[i];
    expect(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2, "a triangle's vertices");
    expect(c.meshes[a.mesh].caster == s.c.meshes[b.mesh].caster, "a mesh's caster flag");
    expect(c.meshes[a.mesh].closed == s.c.meshes[b.mesh].closed, "a mesh's closed flag");
  }
  expect(c.light && c.light->kind == light.kind && c.light->direction == light.direction,
         "the light");
  expect(c.camera.position == s.c.camera.position && c.camera.target == s.c.camera.target &&
             c.camera.width == s.c.camera.width && c.camera.height == s.c.camera.height,
         "the camera");
  expect(c.scale() == s.c.scale(), "the case scale");
  expect(samples.width == s.samples.width && samples.height == s.samples.height, "the size");
  for (std::size_t i = 0; i < std::min(samples.samples.size(), s.samples.samples.size()); ++i) {
    const ViewSample &a = samples.samples[i], &b = s.samples.samples[i];
    expect(a.position == b.position && a.normal == b.normal && a.receiver == b.receiver &&
               a.sample_class == b.sample_class && a.pixel_x == b.pixel_x,
           "a sample");
  }
  std::filesystem::remove_all(folder);
  if (failures == 0) std::printf("reproducer round trip: identical\n");
  return failures == 0 ? 0 : 1;
}
