#pragma once
// The light-assignment stiff scenes of the reference's stiff test, which every port's diff test
// runs too: a small city with lights larger than the scene and around the camera, a near/far
// ratio of 1e-7, and lights tangent to the lists' boxes.
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "shadowcts/case.h"
#include "shadowcts/fixtures.h"

namespace shadowcts::lightassign_test {

// many_lights.2k at 64 x 64 pixels.
inline Case small_city() {
  Case c = make_fixture("many_lights.2k");
  c.camera.width = c.camera.height = 64;
  return c;
}

// A light larger than the scene, lights behind the camera (one reaching into the view, one not),
// one on the near plane and a spot at the eye looking ahead.
inline Case city_with_lights_around_the_camera() {
  Case c = small_city();
  const glm::vec3 eye = c.camera.position;
  const glm::vec3 forward = glm::vec3(c.camera.target) - eye;
  const glm::vec3 ahead =
      forward / std::sqrt(forward.x * forward.x + forward.y * forward.y + forward.z * forward.z);
  RangedLight huge;
  huge.centre = {0, 3, 0};
  huge.range = 1e6f;
  c.ranged_lights.push_back(huge);
  RangedLight behind;
  behind.centre = eye - 5.0f * ahead;
  behind.range = 40.0f;  // reaches into the view from behind the camera
  c.ranged_lights.push_back(behind);
  behind.range = 2.0f;  // does not
  c.ranged_lights.push_back(behind);
  RangedLight near_plane;
  near_plane.centre = eye + c.camera.near_plane * ahead;
  near_plane.range = 30.0f;
  c.ranged_lights.push_back(near_plane);
  RangedLight at_eye;
  at_eye.kind = RangedLightKind::spot;
  at_eye.centre = eye;
  at_eye.range = 60.0f;
  at_eye.direction = ahead;
  at_eye.cone_half_angle = 0.2f;
  c.ranged_lights.push_back(at_eye);
  validate(c);
  return c;
}

// The near plane at 1e-5, the far plane at 100.
inline Case city_with_near_far_1e7() {
  Case c = small_city();
  c.camera.near_plane = 1e-5f;
  c.camera.far_plane = 100.0f;
  validate(c);
  return c;
}

// For every second box: a sphere beyond one face at a power-of-two distance whose range is that
// distance (an exact tie) or one ulp less, and a sphere touching the box's min corner within
// rounding. Spheres like these leave the float filters undecided.
inline std::vector<RangedLight> lights_tangent_to(const std::vector<Aabb>& boxes,
                                                  std::mt19937_64& random) {
  std::vector<RangedLight> lights;
  for (std::size_t k = 0; k < boxes.size(); k += 2) {
    const Aabb& b = boxes[k];
    RangedLight l;
    const int axis = int(random() % 3);
    l.centre = 0.5f * (b.min + b.max);
    l.centre[axis] = b.max[axis] + 0.25f;
    l.range = random() % 2 ? 0.25f : std::nextafter(0.25f, 0.0f);
    lights.push_back(l);
    l.centre = b.min - glm::vec3(0.5f, 0.5f, 0.5f);
    l.range = std::sqrt(0.75f);
    lights.push_back(l);
  }
  return lights;
}

}  // namespace shadowcts::lightassign_test
