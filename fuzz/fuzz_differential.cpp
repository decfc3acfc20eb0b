// libFuzzer target: differential testing. Random small scenes — a caster ground of 2 x 2 cells
// and up to 16 blocker triangles with arbitrary float coordinates — with samples on the ground,
// on blockers and at the shadow images of blocker vertices and edge midpoints (where the
// answer is closest to changing); every registered algorithm against the exact oracle. Any
// robust mismatch is shrunk and saved as a reproducer that `shadowcts run --case` replays.
// Half of the inputs take their samples from a 16 x 16 camera instead (Embree primary rays), so
// that algorithms which need pixel-consistent samples run too.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include "support/conformance_check.h"
#include "support/fuzz_input.h"
#include "support/reproducer.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts;
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  SampleCase s;
  s.c.name = "fuzz.differential";
  s.c.source = "fuzz_differential";
  s.c.parameters.threads = 1;
  ShadowLight light;
  if (in.ConsumeBool()) {
    light.kind = ShadowLightKind::point;
    light.position = {in.ConsumeFloatingPointInRange<float>(-16, 16),
                      in.ConsumeFloatingPointInRange<float>(2, 32),
                      in.ConsumeFloatingPointInRange<float>(-16, 16)};
  } else {
    light.kind = ShadowLightKind::directional;
    light.direction = manifest_stable_direction({in.ConsumeFloatingPointInRange<float>(-1, 1),
                                                 in.ConsumeFloatingPointInRange<float>(0.05f, 1),
                                                 in.ConsumeFloatingPointInRange<float>(-1, 1)});
  }
  s.c.light = light;

  // Ground y = 0 over [-8, 8]^2 in 2 x 2 cells; it casts too (onto blockers' undersides).
  s.begin_mesh("ground", false, true);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      const float x = -8.0f + 8.0f * float(i), z = -8.0f + 8.0f * float(k);
      s.add_triangle({x, 0, z}, {x + 8, 0, z + 8}, {x + 8, 0, z});
      s.add_triangle({x, 0, z}, {x, 0, z + 8}, {x + 8, 0, z + 8});
    }
  // Ground triangle under (x, z): the cell, then which side of its diagonal.
  const auto ground_receiver = [](float x, float z) {
    const int i = std::clamp(int(std::floor((x + 8.0f) / 8.0f)), 0, 1);
    const int k = std::clamp(int(std::floor((z + 8.0f) / 8.0f)), 0, 1);
    const float fx = x - (-8.0f + 8.0f * float(i)), fz = z - (-8.0f + 8.0f * float(k));
    return std::uint32_t(2 * (2 * i + k) + (fx >= fz ? 0 : 1));
  };
  s.begin_mesh("blockers", false, true);
  const std::uint32_t first_blocker = std::uint32_t(s.c.triangles.size());
  const int blockers = in.ConsumeIntegralInRange<int>(1, 16);
  const float size_scale = in.ConsumeFloatingPointInRange<float>(0.01f, 6.0f);
  for (int b = 0; b < blockers; ++b) {
    const glm::vec3 centre{in.ConsumeFloatingPointInRange<float>(-6, 6),
                           in.ConsumeFloatingPointInRange<float>(0.25f, 4),
                           in.ConsumeFloatingPointInRange<float>(-6, 6)};
    const auto corner = [&] {
      return centre + size_scale * glm::vec3(in.ConsumeFloatingPointInRange<float>(-0.5f, 0.5f),
                                             in.ConsumeFloatingPointInRange<float>(-0.5f, 0.5f),
                                             in.ConsumeFloatingPointInRange<float>(-0.5f, 0.5f));
    };
    const glm::vec3 a = corner(), b2 = corner();
    s.add_triangle(a, b2, corner());
  }

  if (in.ConsumeBool()) {
    // Samples seen by a camera above the ground (Embree primary rays, 16 x 16): algorithms that
    // bound samples by their pixels' view frusta (PTSV's implicit clusters, depth tiles) accept
    // only these.
    s.explicit_samples = false;
    s.c.camera.position = {in.ConsumeFloatingPointInRange<float>(-8, 8),
                           in.ConsumeFloatingPointInRange<float>(6, 24),
                           in.ConsumeFloatingPointInRange<float>(-8, 8)};
    s.c.camera.target = {in.ConsumeFloatingPointInRange<float>(-4, 4), 0.0f,
                         in.ConsumeFloatingPointInRange<float>(-4, 4)};
    s.c.camera.up = {0.0f, 0.0f, -1.0f};
    s.c.camera.vertical_fov_degrees = in.ConsumeFloatingPointInRange<float>(20, 100);
    s.c.camera.near_plane = 0.05f;
    s.c.camera.far_plane = 100.0f;
    s.c.camera.width = s.c.camera.height = 16;
    s.samples = generate_view_samples(s.c);
    s.finish();
    check_every_algorithm(s, "fuzz_differential");
    return 0;
  }
  const int sample_count = in.ConsumeIntegralInRange<int>(1, 64);
  for (int k = 0; k < sample_count; ++k) {
    const int kind = in.ConsumeIntegralInRange<int>(0, 2);
    if (kind == 0) {
      const float x = in.ConsumeFloatingPointInRange<float>(-7.5f, 7.5f);
      const float z = in.ConsumeFloatingPointInRange<float>(-7.5f, 7.5f);
      s.add_sample({x, 0.0f, z}, ground_receiver(x, z));
      continue;
    }
    const std::uint32_t t =
        first_blocker + in.ConsumeIntegralInRange<std::uint32_t>(0, std::uint32_t(blockers - 1));
    const Triangle tri = s.c.triangles[t];
    if (kind == 1) {
      float u = in.ConsumeFloatingPointInRange<float>(0, 1),
            v = in.ConsumeFloatingPointInRange<float>(0, 1);
      if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
      s.add_sample(tri.v0 + u * (tri.v1 - tri.v0) + v * (tri.v2 - tri.v0), t);
      continue;
    }
    // The shadow image of a vertex or an edge midpoint on the ground.
    const glm::vec3 feature = in.ConsumeBool() ? tri.v0 : 0.5f * (tri.v1 + tri.v2);
    const glm::dvec3 towards = towards_light(light, feature);
    if (!(towards.y > 0.0)) continue;
    const glm::dvec3 p = glm::dvec3(feature) - (double(feature.y) / towards.y) * towards;
    if (std::fabs(p.x) > 7.5 || std::fabs(p.z) > 7.5) continue;
    s.add_sample({float(p.x), 0.0f, float(p.z)}, ground_receiver(float(p.x), float(p.z)));
  }
  if (s.samples.samples.empty()) return 0;
  s.finish();
  check_every_algorithm(s, "fuzz_differential");
  return 0;
}
