// Checks that a reproducer replays bit for bit: writes one for a small case with two meshes (a
// non-caster receiver and a closed caster box), a directional light and explicit samples, loads
// it the way `shadowcts run --case` does, and compares triangles, mesh flags, light, camera and
// samples exactly (runner/case_round_trip.h; tests/runner/case_round_trip_test.cpp does the same
// for generated fuzz cases). Exit code 0 on success; run by fuzz/run_ci.sh, under the sanitizers,
// before the fuzzers.
#include <cstdio>
#include <filesystem>
#include <string>

#include "fixtures/fuzz/sample_case.h"
#include "runner/case_reproducer.h"
#include "runner/case_round_trip.h"
#include "shadowcts/manifest_direction.h"

int main() {
  using namespace shadowcts;
  fuzzing::SampleCase s;
  s.c.name = "round_trip";
  s.c.source = "reproducer_round_trip";
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = manifest_stable_direction({0.3f, 1.0f, -0.7f});
  s.c.light = light;
  s.begin_mesh("receiver", false);
  const std::uint32_t receiver = s.add_triangle({-4, 0, -4}, {4, 0, -4}, {0, 0, 4});
  s.begin_mesh("box");
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
  if (!s.c.meshes[1].closed) {
    std::fprintf(stderr, "reproducer round trip: the box is not closed\n");
    return 1;
  }
  const std::string manifest = write_reproducer(folder, s.c, s.samples);
  const std::string difference = first_difference(s.c, s.samples, load_case_with_gbuffer(manifest));
  std::filesystem::remove_all(folder);
  if (!difference.empty()) {
    std::fprintf(stderr, "reproducer round trip: %s\n", difference.c_str());
    return 1;
  }
  std::printf("reproducer round trip: identical\n");
  return 0;
}
