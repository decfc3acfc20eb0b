#pragma once
// The camera as the light-assignment algorithms see it: the same frame and pixel mapping as the
// primary rays of generate_view_samples (core/view_samples.cpp), in doubles. View depth is the
// distance along the viewing axis; a pixel (x, y) spans screen coordinates [x, x + 1] x [y, y + 1]
// with row 0 at the top.
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"

namespace shadowcts {

// A screen rectangle in pixel-boundary coordinates and a depth range: the sub-frustum of a tile
// (Paper I) or of a cluster (Paper II).
struct SubFrustum {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // pixel boundaries, y down
  double near_depth = 0, far_depth = 0;
};

class ViewFrustum {
 public:
  explicit ViewFrustum(const Camera& camera);

  double depth(const glm::dvec3& p) const;
  // View-space coordinates: (along right, along up, depth).
  glm::dvec3 to_view(const glm::dvec3& p) const;

  // Tangent of the screen direction at pixel-boundary coordinate x (or y): the view-space x / z
  // (y / z) of points that project there.
  double slope_x(double x) const;
  double slope_y(double y) const;
  // The inverse: the pixel coordinate where view-space slope s projects.
  double pixel_x(double slope) const;
  double pixel_y(double slope) const;

  // The world-space corners of a sub-frustum.
  std::array<glm::dvec3, 8> corners(const SubFrustum& f) const;

  // The float box around the sub-frustum's corners, grown by a margin that covers the rounding
  // of the corner computation (2^-40 of the magnitudes) and rounded outwards to floats.
  Aabb bounding_box(const SubFrustum& f) const;

  // Conservative sphere test against the sub-frustum's six planes: false only when the sphere
  // lies beyond one of them by more than a rounding margin.
  bool sphere_may_meet(const SubFrustum& f, const glm::dvec3& centre, double radius) const;

  double tan_half_fov() const { return tan_half_fov_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  const glm::dvec3& origin() const { return origin_; }

 private:
  glm::dvec3 origin_, right_, up_, forward_;
  double tan_half_fov_ = 1.0, aspect_ = 1.0;
  std::uint32_t width_ = 1, height_ = 1;
};

// Grows a float box to hold p; returns whether it had to.
bool grow_to_contain(Aabb& box, const glm::vec3& p);

}  // namespace shadowcts
