#include "shadowcts/sun_disk_frame.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "shadowcts/errors.h"

namespace shadowcts {

SunDiskFrame sun_disk_frame(const ShadowLight& light, const std::string& source) {
  if (light.kind != ShadowLightKind::sun_disk)
    throw InputError(source, "light", "soft shadows need a sun-disk light");
  const glm::dvec3 d(light.direction);
  if (!(glm::dot(d, d) > 0.0) || !std::isfinite(glm::dot(d, d)))
    throw InputError(source, "light.direction", "must be a finite non-zero vector");
  const double a = double(light.angular_radius);
  if (!(a > 0.0 && a < std::numbers::pi / 2))
    throw InputError(source, "light.angular_radius",
                     "a sun disk needs an angular radius in (0, pi/2) radians");
  SunDiskFrame f;
  f.direction = glm::normalize(d);
  // Any orthonormal pair works (the disk is round); start from the axis least aligned with d.
  const glm::dvec3 helper =
      std::fabs(f.direction.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  f.x_axis = glm::normalize(glm::cross(helper, f.direction));
  f.y_axis = glm::cross(f.direction, f.x_axis);
  f.angular_radius = a;
  f.tan_radius = std::tan(a);
  return f;
}

SunDiskFrame sun_disk_frame(const Case& c) {
  if (!c.light) throw InputError(c.source, "light", "soft shadows need a sun-disk light");
  return sun_disk_frame(*c.light, c.source);
}

}  // namespace shadowcts
