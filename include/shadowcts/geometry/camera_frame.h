#pragma once
// The camera frame every pixel ray is built from (generate_view_samples), in double: one
// definition, so a frame an engine reconstructs against (external results) is the same one.
#include <cmath>
#include <cstdint>

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

// Whether p lies in front of the camera and inside the closed wedge of rays through pixel (x, y)
// of a width x height image (row 0 at the top): where a primary ray through that pixel can hit.
// Bounds built from pixel coordinates alone (implicit cluster bounds) contain a sample only if
// this holds; samples placed by other means (a G-buffer from elsewhere, a fuzzer) may break it.
inline bool in_pixel_wedge(const CameraFrame& f, std::uint32_t width, std::uint32_t height,
                           std::uint32_t x, std::uint32_t y, const glm::dvec3& p) {
  const glm::dvec3 d = p - f.origin;
  const double depth = glm::dot(d, f.forward);
  if (!(depth > 0.0) || x >= width || y >= height) return false;
  const double screen_x = glm::dot(d, f.right) / depth, screen_y = glm::dot(d, f.up) / depth;
  const double aspect = double(width) / double(height);
  const auto column = [&](double c) { return (2.0 * c / width - 1.0) * f.tan_half_fov * aspect; };
  const auto row = [&](double r) { return (1.0 - 2.0 * r / height) * f.tan_half_fov; };
  return screen_x >= column(x) && screen_x <= column(x + 1.0) && screen_y <= row(y) &&
         screen_y >= row(y + 1.0);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
