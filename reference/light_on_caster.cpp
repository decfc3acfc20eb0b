#include "reference/light_on_caster.h"

#include <glm/glm.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "shadowcts/geometry/exact_segment_triangle.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts {

std::vector<std::uint32_t> casters_containing_light(const Case& c) {
  if (!c.light || c.light->kind != ShadowLightKind::point) return {};
  const glm::vec3 l = c.light->position;
  const glm::dvec3 light(l);
  // In index order: each range's finds, joined left to right.
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, c.triangles.size(), 16384), std::vector<std::uint32_t>(),
      [&](const tbb::blocked_range<std::size_t>& r, std::vector<std::uint32_t> found) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Triangle& t = c.triangles[i];
          // A closed triangle holds only points of its box (float comparisons are exact): this
          // leaves the exact tests to the few triangles around the light.
          if (glm::any(glm::lessThan(l, glm::min(glm::min(t.v0, t.v1), t.v2))) ||
              glm::any(glm::greaterThan(l, glm::max(glm::max(t.v0, t.v1), t.v2))))
            continue;
          if (t.mesh >= c.meshes.size() || !c.meshes[t.mesh].caster) continue;
          const glm::dvec3 a(t.v0), b(t.v1), d(t.v2);
          // Exact signs of the float inputs (shared expansions): in the plane, then in the
          // closed triangle; zero area is no caster.
          if (geometry::detail::projection_axis(a, b, d) < 0 ||
              geometry::orientation(a, b, d, light) != 0)
            continue;
          if (geometry::detail::point_in_coplanar_triangle(light, a, b, d))
            found.push_back(std::uint32_t(i));
        }
        return found;
      },
      [](std::vector<std::uint32_t> left, const std::vector<std::uint32_t>& right) {
        left.insert(left.end(), right.begin(), right.end());
        return left;
      });
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
