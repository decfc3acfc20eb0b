#include "reference/softtile/fragment_occlusion.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/disk_reach.h"

namespace shadowcts::softtile {

bool triangle_edges(const FragmentSetup& fragment, const std::array<glm::vec3, 3>& light_space,
                    std::array<glm::vec3, 3>& edges) {
  const float vertices[9] = {light_space[0].x, light_space[0].y, light_space[0].z,
                             light_space[1].x, light_space[1].y, light_space[1].z,
                             light_space[2].x, light_space[2].y, light_space[2].z};
  if (beside_disk(fragment.position.x, fragment.position.y, fragment.position.z,
                  light_space_box(vertices), fragment.reach_per_height))
    return false;
  std::array<glm::vec3, 3> h;
  bool any_front = false;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 tmp = light_space[i] - fragment.position;
    const float x = tmp.x * fragment.inverse_scale, y = tmp.y * fragment.inverse_scale;
    // Rotating the triangle by the angle rotates the grid by its opposite: the disk is round.
    h[i] = {fragment.cos_rotation * x - fragment.sin_rotation * y,
            fragment.sin_rotation * x + fragment.cos_rotation * y, tmp.z};
    any_front = any_front || tmp.z > 0.0f;
  }
  if (!any_front) return false;
  const float det = glm::dot(h[0], glm::cross(h[1], h[2]));
  if (det == 0.0f || !std::isfinite(det)) return false;
  const float sign = det > 0.0f ? 1.0f : -1.0f;
  for (int i = 0; i < 3; ++i) {
    edges[i] = sign * glm::cross(h[i], h[(i + 1) % 3]);
    // The disk lies entirely outside this edge: a X + b Y + c < -|(a, b)| on the whole unit disk.
    if (edges[i].z < 0.0f &&
        edges[i].z * edges[i].z > edges[i].x * edges[i].x + edges[i].y * edges[i].y)
      return false;
  }
  return true;
}

}  // namespace shadowcts::softtile
