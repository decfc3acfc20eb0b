#pragma once
// The camera as the cluster keys and the hierarchical depth buffer see it: view depth along the
// viewing axis and screen coordinates at unit depth, the same frame in which the view samples were
// cast (core/view_samples.cpp). A rectangle of pixels and a depth interval span a frustum cell;
// Sintorn 2014 tests nodes as boxes in clip space, and a clip-space box is exactly such a cell, so
// testing a plane against the cell's eight world-space corners is the paper's box test without the
// rounding of a projection matrix.
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts::ptsv {

struct ViewFrame {
  glm::dvec3 origin{0.0}, right{0.0}, up{0.0}, forward{0.0};
  double tan_half_fov = 0.0, aspect = 1.0;
  std::uint32_t width = 0, height = 0;  // the view samples' image
};

inline ViewFrame make_view_frame(const Camera& cam, std::uint32_t width, std::uint32_t height) {
  const CameraFrame camera = camera_frame(cam);
  ViewFrame f;
  f.origin = camera.origin;
  f.forward = camera.forward;
  f.right = camera.right;
  f.up = camera.up;
  f.tan_half_fov = camera.tan_half_fov;
  f.width = width;
  f.height = height;
  f.aspect = double(width) / double(height);
  return f;
}

// A point in view coordinates: depth along the viewing axis, and (screen_x, screen_y) = lateral
// offsets divided by depth (the point lies on the ray forward + screen_x right + screen_y up).
struct ViewPoint {
  double depth = 0.0, screen_x = 0.0, screen_y = 0.0;
};

inline ViewPoint to_view(const ViewFrame& f, const glm::dvec3& p) {
  const glm::dvec3 d = p - f.origin;
  ViewPoint v;
  v.depth = glm::dot(d, f.forward);
  v.screen_x = glm::dot(d, f.right) / v.depth;
  v.screen_y = glm::dot(d, f.up) / v.depth;
  return v;
}

// Screen coordinate of the left edge of pixel column x (x = width: the image's right edge).
inline double screen_x_of_column(const ViewFrame& f, double x) {
  return shadowcts::screen_x_of_column(f.tan_half_fov, f.width, f.height, x);
}

// Screen coordinate of the top edge of pixel row y (rows grow downwards).
inline double screen_y_of_row(const ViewFrame& f, double y) {
  return shadowcts::screen_y_of_row(f.tan_half_fov, f.height, y);
}

// Pixels [x0, x1) x [y0, y1) between view depths depth0 <= depth1.
struct FrustumCell {
  std::uint32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  double depth0 = 0.0, depth1 = 0.0;
};

// The eight corners of the cell: the cell is their convex hull.
inline std::array<glm::dvec3, 8> cell_corners(const ViewFrame& f, const FrustumCell& cell) {
  const double sx[2] = {screen_x_of_column(f, cell.x0), screen_x_of_column(f, cell.x1)};
  const double sy[2] = {screen_y_of_row(f, cell.y1), screen_y_of_row(f, cell.y0)};
  const double depth[2] = {cell.depth0, cell.depth1};
  std::array<glm::dvec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 ray = f.forward + sx[i & 1] * f.right + sy[(i >> 1) & 1] * f.up;
    corners[std::size_t(i)] = f.origin + depth[(i >> 2) & 1] * ray;
  }
  return corners;
}

// Whether p lies laterally inside the wedge of pixels [x0, x1) x [y0, y1) (in front of the
// camera). The implicit bounds of the cluster keys and the depth-buffer tiles are built from pixel
// coordinates, so they contain a sample only if this holds; G-buffers from elsewhere may break it.
inline bool inside_pixel_wedge(const ViewFrame& f, const ViewPoint& v, std::uint32_t x0,
                               std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) {
  return in_pixel_span(f.tan_half_fov, f.width, f.height, v.depth, v.screen_x, v.screen_y, x0, x1,
                       y0, y1);
}

}  // namespace shadowcts::ptsv
