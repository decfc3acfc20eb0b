#pragma once
// A small hand-built light-assignment case: a ground quad in the plane y = 0 seen from above,
// so that every sample has y == 0 exactly and normal (0, 1, 0).
#include "shadowcts/case.h"

namespace shadowcts::testing {

inline Case ground_quad_case() {
  Case c;
  c.name = "ground_quad";
  c.source = "test:ground_quad";
  c.meshes.push_back({"ground", false, true});
  const glm::vec3 a(-8, 0, -8), b(8, 0, -8), d(8, 0, 8), e(-8, 0, 8);
  c.triangles.push_back({a, e, d, 0});
  c.triangles.push_back({a, d, b, 0});
  c.camera.position = {0.5f, 12.0f, 0.25f};
  c.camera.target = {0.0f, 0.0f, 0.0f};
  c.camera.up = {0.0f, 0.0f, -1.0f};
  c.camera.vertical_fov_degrees = 60.0f;
  c.camera.width = c.camera.height = 48;
  return c;
}

inline RangedLight sphere_light(glm::vec3 centre, float range) {
  RangedLight l;
  l.centre = centre;
  l.range = range;
  return l;
}

inline RangedLight spot_light(glm::vec3 centre, float range, glm::vec3 axis, float half_angle) {
  RangedLight l = sphere_light(centre, range);
  l.kind = RangedLightKind::spot;
  l.direction = axis;
  l.cone_half_angle = half_angle;
  return l;
}

}  // namespace shadowcts::testing
