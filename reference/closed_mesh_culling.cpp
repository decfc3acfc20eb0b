#include "reference/closed_mesh_culling.h"

#include <limits>

#include <glm/common.hpp>

namespace shadowcts {

std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples) {
  const std::size_t n = c.meshes.size();
  std::vector<glm::vec3> lo(n, glm::vec3(std::numeric_limits<float>::infinity()));
  std::vector<glm::vec3> hi(n, glm::vec3(-std::numeric_limits<float>::infinity()));
  for (const Triangle& t : c.triangles) {
    if (t.mesh >= n) continue;
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo[t.mesh] = glm::min(lo[t.mesh], v);
      hi[t.mesh] = glm::max(hi[t.mesh], v);
    }
  }
  // Float comparisons of float coordinates are exact: "inside the box" is decided exactly.
  auto in_box = [&](std::size_t m, const glm::vec3& p) {
    return p.x >= lo[m].x && p.x <= hi[m].x && p.y >= lo[m].y && p.y <= hi[m].y && p.z >= lo[m].z &&
           p.z <= hi[m].z;
  };
  std::vector<bool> safe(n, false);
  for (std::size_t m = 0; m < n; ++m) {
    if (!c.meshes[m].closed || !c.meshes[m].caster) continue;
    bool clear =
        !(c.light && c.light->kind == ShadowLightKind::point && in_box(m, c.light->position));
    for (const ViewSample& s : samples.samples)
      if (clear && s.sample_class == SampleClass::regular && in_box(m, s.position)) clear = false;
    safe[m] = clear;
  }
  return safe;
}

}  // namespace shadowcts
