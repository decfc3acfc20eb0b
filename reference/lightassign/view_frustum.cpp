#include "reference/lightassign/view_frustum.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts {
namespace {

// Relative margin for quantities computed in a handful of double operations from float inputs:
// their rounding error is below 2^-48 of the magnitudes involved.
constexpr double rounding_margin = 0x1p-40;

}  // namespace

ViewFrustum::ViewFrustum(const Camera& camera) {
  // The frame the view samples were cast in.
  const CameraFrame frame = camera_frame(camera);
  origin_ = frame.origin;
  forward_ = frame.forward;
  right_ = frame.right;
  up_ = frame.up;
  tan_half_fov_ = frame.tan_half_fov;
  aspect_ = frame.aspect;
  width_ = camera.width;
  height_ = camera.height;
}

double ViewFrustum::depth(const glm::dvec3& p) const {
  return glm::dot(p - origin_, forward_);
}

glm::dvec3 ViewFrustum::to_view(const glm::dvec3& p) const {
  const glm::dvec3 v = p - origin_;
  return {glm::dot(v, right_), glm::dot(v, up_), glm::dot(v, forward_)};
}

double ViewFrustum::slope_x(double x) const {
  return (2.0 * x / width_ - 1.0) * tan_half_fov_ * aspect_;
}

double ViewFrustum::slope_y(double y) const {
  return (1.0 - 2.0 * y / height_) * tan_half_fov_;
}

double ViewFrustum::pixel_x(double slope) const {
  return (slope / (tan_half_fov_ * aspect_) + 1.0) * 0.5 * width_;
}

double ViewFrustum::pixel_y(double slope) const {
  return (1.0 - slope / tan_half_fov_) * 0.5 * height_;
}

std::array<glm::dvec3, 8> ViewFrustum::corners(const SubFrustum& f) const {
  std::array<glm::dvec3, 8> out;
  int n = 0;
  for (const double d : {f.near_depth, f.far_depth})
    for (const double y : {f.y0, f.y1})
      for (const double x : {f.x0, f.x1})
        out[std::size_t(n++)] = origin_ + d * (forward_ + slope_x(x) * right_ + slope_y(y) * up_);
  return out;
}

Aabb ViewFrustum::bounding_box(const SubFrustum& f) const {
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
  double magnitude = glm::length(origin_);
  for (const glm::dvec3& c : corners(f)) {
    low = glm::min(low, c);
    high = glm::max(high, c);
    magnitude = std::max(magnitude, glm::length(c) + glm::length(c - origin_));
  }
  const double margin = rounding_margin * magnitude;
  Aabb box;
  for (int i = 0; i < 3; ++i) {
    box.min[i] = float_below(low[i] - margin);
    box.max[i] = float_above(high[i] + margin);
  }
  return box;
}

bool ViewFrustum::sphere_may_meet(const SubFrustum& f, const glm::dvec3& centre,
                                  double radius) const {
  const glm::dvec3 v = to_view(centre);
  const double margin =
      rounding_margin * (glm::length(centre) + glm::length(origin_) + radius + f.far_depth);
  const double reach = radius + margin;
  // Depth planes.
  if (v.z < f.near_depth - reach || v.z > f.far_depth + reach) return false;
  // Side planes through the eye: x >= sx0 z, x <= sx1 z, y <= sy0 z, y >= sy1 z; the signed
  // distance of the centre to the plane n . v = 0 is n . v / |n|.
  const double sx0 = slope_x(f.x0), sx1 = slope_x(f.x1);
  const double sy0 = slope_y(f.y0), sy1 = slope_y(f.y1);  // sy0 > sy1: y grows downwards
  auto outside = [&](double along, double slope) {
    // Signed distance of (along, depth) from the plane along = slope * depth, positive inside
    // when along - slope * depth >= 0.
    return (along - slope * v.z) / std::sqrt(1.0 + slope * slope) < -reach;
  };
  if (outside(v.x, sx0)) return false;
  if (outside(-v.x, -sx1)) return false;
  if (outside(-v.y, -sy0)) return false;
  if (outside(v.y, sy1)) return false;
  return true;
}

bool grow_to_contain(Aabb& box, const glm::vec3& p) {
  bool grew = false;
  for (int i = 0; i < 3; ++i) {
    if (p[i] < box.min[i]) box.min[i] = p[i], grew = true;
    if (p[i] > box.max[i]) box.max[i] = p[i], grew = true;
  }
  return grew;
}

}  // namespace shadowcts
