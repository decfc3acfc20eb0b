#include "reference/ptsv/node_test.h"

#include <algorithm>

#include "shadowcts/geometry/exact_orientation.h"

namespace shadowcts::ptsv {

NodeTolerances NodeTolerances::for_bounds(double node_bound, double scene_bound) {
  NodeTolerances t;
  // A plane value is a dot product of a unit normal (relative error ~2^-52) with a difference of
  // coordinates below 2 * bound; its rounding is below 2^-48 * bound. 2^-36 leaves a wide margin
  // and stays far below the ambiguity band (2^-24 * scale at its finest).
  t.rounding = node_bound * 0x1p-36;
  t.accept_bias = trivial_accept_bias(scene_bound);
  return t;
}

double scene_bound(const Case& c, const ViewSamples& samples) {
  double bound = c.scale();
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular)
      for (int k = 0; k < 3; ++k) bound = std::max(bound, std::fabs(double(s.position[k])));
  return bound;
}

PlaneRange plane_range(const Plane& plane, const std::array<glm::dvec3, 8>& corners) {
  PlaneRange r{plane.at(corners[0]), plane.at(corners[0])};
  for (std::size_t i = 1; i < 8; ++i) {
    const double value = plane.at(corners[i]);
    r.low = std::min(r.low, value);
    r.high = std::max(r.high, value);
  }
  return r;
}

PlaneRange plane_range(const Plane& plane, const WorldBox& box) {
  glm::dvec3 reject_point, accept_point;
  for (int k = 0; k < 3; ++k) {
    const bool positive = plane.normal[k] >= 0.0;
    reject_point[k] = positive ? box.lo[k] : box.hi[k];
    accept_point[k] = positive ? box.hi[k] : box.lo[k];
  }
  return {plane.at(reject_point), plane.at(accept_point)};
}

bool outside_plane_exactly(const ShadowVolume& volume, int k, const glm::vec3& p) {
  const ExactVolumePlanes& e = volume.exact;
  if (k == 3) {
    // n = (q - p0) x (r - p0): det[q - p0, r - p0, p - p0].
    return e.triangle_outside * geometry::orientation(glm::dvec3(e.vertices[0]),
                                                      glm::dvec3(e.vertices[1]),
                                                      glm::dvec3(e.vertices[2]), glm::dvec3(p)) >
           0;
  }
  static constexpr int first[3] = {0, 1, 0}, second[3] = {1, 2, 2};
  const glm::vec3& a = e.vertices[std::size_t(first[k])];
  const glm::vec3& b = e.vertices[std::size_t(second[k])];
  // n = (b - a) x (L - a): det[b - a, L - a, p - a]; or n = (b - a) x d: -det[b - a, p - a, d].
  const glm::dvec3 da(a), db(b), dp(p), dl(e.light);
  const int sign = e.directional ? -geometry::orientation_towards(da, db, dp, dl)
                                 : geometry::orientation(da, db, dl, dp);
  return e.edge_outside[std::size_t(k)] * sign > 0;
}

}  // namespace shadowcts::ptsv
