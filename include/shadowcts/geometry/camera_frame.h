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

// Screen coordinates (lateral offset over view depth) of the pixel edges of a width x height
// image: the left edge of column x (x = width: the image's right edge), the top edge of row y
// (rows grow downwards).
inline double screen_x_of_column(double tan_half_fov, std::uint32_t width, std::uint32_t height,
                                 double x) {
  return (2.0 * x / width - 1.0) * tan_half_fov * (double(width) / double(height));
}
inline double screen_y_of_row(double tan_half_fov, std::uint32_t height, double y) {
  return (1.0 - 2.0 * y / height) * tan_half_fov;
}

// Whether a point at view depth `depth` and screen coordinates (screen_x, screen_y) lies inside
// the closed wedge of rays through pixels [x0, x1) x [y0, y1), in front of the camera.
inline bool in_pixel_span(double tan_half_fov, std::uint32_t width, std::uint32_t height,
                          double depth, double screen_x, double screen_y, std::uint32_t x0,
                          std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) {
  return depth > 0.0 && screen_x >= screen_x_of_column(tan_half_fov, width, height, x0) &&
         screen_x <= screen_x_of_column(tan_half_fov, width, height, x1) &&
         screen_y <= screen_y_of_row(tan_half_fov, height, y0) &&
         screen_y >= screen_y_of_row(tan_half_fov, height, y1);
}

// Whether p lies in front of the camera and inside the closed wedge of rays through pixel (x, y):
// where a primary ray through that pixel can hit. Bounds built from pixel coordinates alone
// (implicit cluster bounds) contain a sample only if this holds; samples placed by other means (a
// G-buffer from elsewhere, a fuzzer) may break it.
inline bool in_pixel_wedge(const CameraFrame& f, std::uint32_t width, std::uint32_t height,
                           std::uint32_t x, std::uint32_t y, const glm::dvec3& p) {
  const glm::dvec3 d = p - f.origin;
  const double depth = glm::dot(d, f.forward);
  if (!(depth > 0.0) || x >= width || y >= height) return false;
  return in_pixel_span(f.tan_half_fov, width, height, depth, glm::dot(d, f.right) / depth,
                       glm::dot(d, f.up) / depth, x, x + 1, y, y + 1);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
