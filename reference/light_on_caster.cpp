#include "reference/light_on_caster.h"

#include "shadowcts/geometry/exact_segment_triangle.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts {

std::vector<std::uint32_t> casters_containing_light(const Case& c) {
  std::vector<std::uint32_t> found;
  if (!c.light || c.light->kind != ShadowLightKind::point) return found;
  const glm::dvec3 light(c.light->position);
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    const Triangle& t = c.triangles[i];
    if (t.mesh >= c.meshes.size() || !c.meshes[t.mesh].caster) continue;
    const glm::dvec3 a(t.v0), b(t.v1), d(t.v2);
    // Exact signs of the float inputs (shared expansions): in the plane, then in the closed
    // triangle; zero area is no caster.
    if (geometry::detail::projection_axis(a, b, d) < 0 ||
        geometry::orientation(a, b, d, light) != 0)
      continue;
    if (geometry::detail::point_in_coplanar_triangle(light, a, b, d))
      found.push_back(std::uint32_t(i));
  }
  return found;
}

std::uint64_t shadow_samples_by_light_on_caster(const Case& c, const ViewSamples& samples,
                                                std::vector<std::uint8_t>& shadowed) {
  const std::vector<std::uint32_t> on_light = casters_containing_light(c);
  if (on_light.empty()) return 0;
  std::uint64_t changed = 0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular || shadowed[i]) continue;
    if (on_light.size() == 1 && on_light.front() == s.receiver) continue;
    shadowed[i] = 1;
    ++changed;
  }
  return changed;
}

}  // namespace shadowcts
