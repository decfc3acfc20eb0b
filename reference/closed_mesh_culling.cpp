#include "reference/closed_mesh_culling.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <glm/common.hpp>

#include "shadowcts/thread_limit.h"

namespace shadowcts {

std::vector<bool> meshes_safe_for_face_culling(const Case& c, const ViewSamples& samples) {
  const std::size_t n = c.meshes.size();
  std::vector<bool> safe(n, false);
  bool any_closed_caster = false;
  for (const Mesh& m : c.meshes) any_closed_caster = any_closed_caster || (m.closed && m.caster);
  if (!any_closed_caster) return safe;

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
  // The regular samples sorted by x: only those in a box's x range can lie in the box. Scanning
  // every sample for every closed mesh took half a second on a million-triangle scene.
  std::vector<glm::vec3> points;
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular) points.push_back(s.position);
  std::vector<char> clear(n, 0);
  run_with_thread_limit(c.parameters.threads, [&] {
    tbb::parallel_sort(points.begin(), points.end(),
                       [](const glm::vec3& a, const glm::vec3& b) { return a.x < b.x; });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& range) {
      for (std::size_t m = range.begin(); m != range.end(); ++m) {
        if (!c.meshes[m].closed || !c.meshes[m].caster) continue;
        if (c.light && c.light->kind == ShadowLightKind::point && in_box(m, c.light->position))
          continue;
        auto p = std::lower_bound(points.begin(), points.end(), lo[m].x,
                                  [](const glm::vec3& q, float x) { return q.x < x; });
        bool holds_sample = false;
        for (; p != points.end() && p->x <= hi[m].x && !holds_sample; ++p)
          holds_sample = in_box(m, *p);
        clear[m] = holds_sample ? 0 : 1;
      }
    });
  });
  for (std::size_t m = 0; m < n; ++m) safe[m] = clear[m] != 0;
  return safe;
}

}  // namespace shadowcts
