#include "reference/stencil/crossing_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "reference/stencil/robust_orientation.h"

namespace shadowcts::stencil {
namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon();

double max_abs(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// How far the computed extrusion of x lies from the exact line through x and the light (or along
// the light's direction), which lies in every exact side-quad plane through x: a few roundings of
// the coordinates (and of the normalized direction), with a wide margin.
double extrusion_error(const Extrusion& extrusion, const glm::dvec3& x) {
  if (extrusion.directional) return 64.0 * epsilon * (max_abs(x) + extrusion.shift);
  const double light = max_abs(extrusion.light);
  return 64.0 * epsilon * (light + extrusion.scale * (max_abs(x) + light));
}

// An upper bound on |u x v| for the exact u and v of which these are rounded differences.
double cross_norm_upper(const glm::dvec3& u, const glm::dvec3& v) {
  const glm::dvec3 n = glm::cross(u, v);
  const glm::dvec3 size(std::fabs(u.y * v.z) + std::fabs(u.z * v.y),
                        std::fabs(u.z * v.x) + std::fabs(u.x * v.z),
                        std::fabs(u.x * v.y) + std::fabs(u.y * v.x));
  const glm::dvec3 bound = glm::abs(n) + 8.0 * epsilon * size;
  return glm::length(bound) * (1.0 + 8.0 * epsilon);
}

// A lower bound on the eye's distance from a side quad's exact plane (0 when none is proven).
double eye_distance_lower(const VolumeFace& quad, const HardShadowLight& light,
                          const glm::dvec3& eye) {
  const glm::dvec3& to = quad.v[0];
  const glm::dvec3& from = quad.v[1];
  const glm::dvec3 zero(0.0);
  // The determinants side_quad_plane_side takes the sign of: |det| = |normal| * distance.
  const DeterminantEstimate det =
      light.directional ? estimate_determinant(from, to, light.direction, zero, eye, to)
                        : estimate_determinant(from, to, light.position, to, eye, to);
  const double normal =
      cross_norm_upper(from - to, light.directional ? light.direction : light.position - to);
  const double distance = (std::fabs(det.value) - det.error) / normal * (1.0 - 8.0 * epsilon);
  return distance > 0.0 ? distance : 0.0;  // also NaN (overflow) -> 0
}

// A lower bound on the eye's distance from the plane of a cap (its own triangle).
double eye_distance_to_cap_plane(const VolumeFace& cap, const glm::dvec3& eye) {
  const DeterminantEstimate det =
      estimate_determinant(cap.v[1], cap.v[0], cap.v[2], cap.v[0], eye, cap.v[0]);
  const double normal = cross_norm_upper(cap.v[1] - cap.v[0], cap.v[2] - cap.v[0]);
  const double distance = (std::fabs(det.value) - det.error) / normal * (1.0 - 8.0 * epsilon);
  return distance > 0.0 ? distance : 0.0;
}

// The smallest altitude of triangle abc, approximately (callers keep a factor 2 margin).
double smallest_altitude(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
  return longest > 0.0 ? glm::length(glm::cross(b - a, c - a)) / longest : 0.0;
}

CrossingReach side_quad_reach(const VolumeFace& quad, CountingMode mode, const Extrusion& extrusion,
                              const HardShadowLight& light, const glm::dvec3& eye,
                              double sample_reach) {
  CrossingReach anywhere;
  const double delta =
      std::max(extrusion_error(extrusion, quad.v[0]), extrusion_error(extrusion, quad.v[1]));
  const double a = eye_distance_lower(quad, light, eye);
  if (!(a > 0.0) || !std::isfinite(delta)) return anywhere;
  if (mode == CountingMode::z_fail) {
    // The triangles turn about their exact vertices by at most delta over their altitudes (a
    // linear deviation of at most delta at two vertices, 0 at the third): tan(angle) <=
    // 2 delta / h, with h halved against its own rounding.
    const double h = std::min(smallest_altitude(quad.v[0], quad.v[1], quad.v[2]),
                              smallest_altitude(quad.v[0], quad.v[2], quad.v[3]));
    if (!(h > 0.0)) return anywhere;
    const double tilt = 4.0 * delta / h;
    double reach = sample_reach;
    for (const glm::dvec3& v : quad.v) reach = std::max(reach, glm::length(v - eye));
    reach *= 1.0 + 1e-9;
    if (!(a > delta + tilt * reach)) return anywhere;
  }
  const double slack = delta / a * (1.0 + 1e-9);
  if (!(slack <= max_slack)) return anywhere;
  // The triangles lie within delta of the plane.
  return {CrossingReach::Kind::bounded, slack, std::max(0.0, a - 2.0 * delta)};
}

}  // namespace

CrossingReach crossing_reach(const VolumeFace& face, const FaceEyeSides& eye_side,
                             CountingMode mode, const Extrusion& extrusion,
                             const HardShadowLight& light, const glm::dvec3& eye,
                             double sample_reach) {
  if (eye_side.side[0] == 0)  // z-pass: e+ lies past the plane, so never an entry before p
    return {
        mode == CountingMode::z_pass ? CrossingReach::Kind::never : CrossingReach::Kind::anywhere,
        0.0};
  if (!face.is_quad())
    return {CrossingReach::Kind::bounded, 0.0, eye_distance_to_cap_plane(face, eye)};
  return side_quad_reach(face, mode, extrusion, light, eye, sample_reach);
}

}  // namespace shadowcts::stencil
