// libFuzzer target: degenerate triangles at huge and tiny scales. The bytes choose triangles
// that are zero-area (collinear, a repeated vertex, all three equal), slivers of relative width
// down to 1e-7, needles one ulp wide, or ordinary; a scale 2^k (k in [-60, 60], exact), a point,
// directional or sun-disk light, and samples on the triangles and beside them. No algorithm may
// crash, throw or answer NaN (soft output: a fraction in [0, 1]); every hard-shadow algorithm
// must agree with the exact oracle on robust samples (zero-area triangles cast no shadow).
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/geometric.hpp>

#include "support/conformance_check.h"
#include "support/fuzz_input.h"
#include "support/reproducer.h"

namespace shadowcts::fuzzing {
namespace {

// A triangle of the kind the bytes choose, in unscaled coordinates (|x| <= 8).
Triangle degenerate_triangle(FuzzedDataProvider& in) {
  const glm::vec3 a = dyadic_point(in, 128, 4), b = dyadic_point(in, 128, 4);
  switch (in.ConsumeIntegralInRange<int>(0, 6)) {
    case 0:  // collinear: c on the line ab, possibly outside the segment
      return {a, b, a + (float(in.ConsumeIntegralInRange<int>(-16, 32)) / 16.0f) * (b - a)};
    case 1:  // a repeated vertex, in any position
      switch (in.ConsumeIntegralInRange<int>(0, 2)) {
        case 0:
          return {a, a, b};
        case 1:
          return {a, b, a};
        default:
          return {b, a, a};
      }
    case 2:  // a point
      return {a, a, a};
    case 3: {  // sliver: apex 1e-7 .. 1e-3 of the base length off the base's midpoint
      const double width = std::pow(10.0, -double(in.ConsumeIntegralInRange<int>(3, 7))) *
                           glm::length(glm::dvec3(b) - glm::dvec3(a));
      glm::dvec3 off(0.0);
      off[in.ConsumeIntegralInRange<int>(0, 2)] = width;
      return {a, b, glm::vec3(0.5 * (glm::dvec3(a) + glm::dvec3(b)) + off)};
    }
    case 4:  // needle: the third vertex one ulp from the second
      return {a, b, ulp_jitter(in, b, 1)};
    default:
      return {a, b, dyadic_point(in, 128, 4)};
  }
}

glm::vec3 scaled(const glm::vec3& v, int exponent) {
  return {std::ldexp(v.x, exponent), std::ldexp(v.y, exponent), std::ldexp(v.z, exponent)};
}

}  // namespace
}  // namespace shadowcts::fuzzing

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts;
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  const int exponent = in.ConsumeIntegralInRange<int>(-60, 60);
  SampleCase s;
  s.c.name = "fuzz.degenerate";
  s.c.source = "fuzz_degenerate";
  s.c.parameters.threads = 1;
  ShadowLight light;
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      light.kind = ShadowLightKind::directional;
      light.direction = manifest_stable_direction(
          glm::vec3(dyadic(in, 4, 2), 1.0f + dyadic(in, 3, 2), dyadic(in, 4, 2)));
      break;
    case 1:
      light.kind = ShadowLightKind::sun_disk;
      light.direction = manifest_stable_direction(
          glm::vec3(dyadic(in, 4, 2), 1.0f + dyadic(in, 3, 2), dyadic(in, 4, 2)));
      light.angular_radius = float(in.ConsumeFloatingPointInRange<double>(1e-6, 0.785));
      break;
    default:
      light.kind = ShadowLightKind::point;
      light.position = scaled(dyadic_point(in, 256, 4) + glm::vec3(0, 16, 0), exponent);
      break;
  }
  s.c.light = light;

  s.begin_mesh("receiver", false, false);
  const std::uint32_t receiver = s.add_triangle(
      scaled({-8, -8, -8}, exponent), scaled({8, -8, -8}, exponent), scaled({0, -8, 8}, exponent));
  s.begin_mesh("degenerate", false);
  const int triangles = in.ConsumeIntegralInRange<int>(1, 24);
  for (int k = 0; k < triangles; ++k) {
    const Triangle t = degenerate_triangle(in);
    s.add_triangle(scaled(t.v0, exponent), scaled(t.v1, exponent), scaled(t.v2, exponent));
  }

  const int sample_count = in.ConsumeIntegralInRange<int>(1, 32);
  for (int k = 0; k < sample_count; ++k) {
    if (in.ConsumeBool()) {
      // On a triangle (a dyadic barycentric point), which is then the sample's receiver.
      const std::uint32_t t =
          in.ConsumeIntegralInRange<std::uint32_t>(1, std::uint32_t(s.c.triangles.size() - 1));
      const Triangle& tri = s.c.triangles[t];
      const float u = float(in.ConsumeIntegralInRange<int>(0, 8)) / 16.0f;
      const float v = float(in.ConsumeIntegralInRange<int>(0, 8)) / 16.0f;
      s.add_sample(tri.v0 + u * (tri.v1 - tri.v0) + v * (tri.v2 - tri.v0), t);
    } else {
      s.add_sample(scaled(dyadic_point(in, 128, 4) - glm::vec3(0, 4, 0), exponent), receiver);
    }
  }
  s.finish();
  check_every_algorithm(s, "fuzz_degenerate");
  return 0;
}
