#pragma once
// The camera frame every pixel ray is built from (generate_view_samples), in double: one
// definition, so a frame an engine reconstructs against (external results) is the same one.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

struct CameraFrame {
  glm::dvec3 origin, right, up, forward;
  double tan_half_fov, aspect;
};

inline CameraFrame camera_frame(const Camera& cam) {
  CameraFrame f;
  f.origin = glm::dvec3(cam.position);
  f.forward = glm::normalize(glm::dvec3(cam.target) - f.origin);
  f.right = glm::normalize(glm::cross(f.forward, glm::dvec3(cam.up)));
  f.up = glm::cross(f.right, f.forward);
  f.tan_half_fov = std::tan(double(cam.vertical_fov_degrees) * 3.14159265358979323846 / 360.0);
  f.aspect = double(cam.width) / double(cam.height);
  return f;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
