#include "reference/light_on_caster.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace shadowcts {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

Epick::Point_3 point(const glm::vec3& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

}  // namespace

std::vector<std::uint32_t> casters_containing_light(const Case& c) {
  std::vector<std::uint32_t> found;
  if (!c.light || c.light->kind != ShadowLightKind::point) return found;
  const Epick::Point_3 light = point(c.light->position);
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    const Triangle& t = c.triangles[i];
    if (t.mesh >= c.meshes.size() || !c.meshes[t.mesh].caster) continue;
    const Epick::Point_3 a = point(t.v0), b = point(t.v1), d = point(t.v2);
    if (CGAL::collinear(a, b, d) || CGAL::orientation(a, b, d, light) != CGAL::COPLANAR) continue;
    // In the plane: inside or on every edge, each judged against the opposite vertex's side.
    if (CGAL::coplanar_orientation(a, b, d, light) != CGAL::NEGATIVE &&
        CGAL::coplanar_orientation(b, d, a, light) != CGAL::NEGATIVE &&
        CGAL::coplanar_orientation(d, a, b, light) != CGAL::NEGATIVE)
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
