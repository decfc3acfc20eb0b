#include "reference/shadowmap/cube_map.h"

#include <cmath>

namespace shadowcts::shadowmap {

LightView cube_face_view(const glm::dvec3& light, int face, std::uint32_t resolution, double near) {
  const int axis = face / 2;
  const double sign = face % 2 == 0 ? 1.0 : -1.0;
  LightView view;
  view.perspective = true;
  view.origin = light;
  view.forward = glm::dvec3(0.0);
  view.forward[axis] = sign;
  // Any orthonormal (right, up) across the face works: depth does not depend on it.
  view.right = glm::dvec3(0.0);
  view.right[(axis + 1) % 3] = 1.0;
  view.up = glm::dvec3(0.0);
  view.up[(axis + 2) % 3] = 1.0;
  view.half_extent = 1.0;
  view.near = near;
  view.resolution = resolution;
  return view;
}

int cube_face_of(const glm::dvec3& d) {
  const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  if (ax >= ay && ax >= az) return d.x >= 0.0 ? 0 : 1;
  if (ay >= az) return d.y >= 0.0 ? 2 : 3;
  return d.z >= 0.0 ? 4 : 5;
}

}  // namespace shadowcts::shadowmap
