// The closed-form single-triangle oracle: one convex polygon against the disk, no arrangement.
#include <algorithm>
#include <numbers>

#include "oracles/soft_shadow/disk_polygon_area.h"
#include "oracles/soft_shadow/sun_disk_projection.h"
#include "shadowcts/soft_shadow_oracle.h"

namespace shadowcts {

double single_triangle_visible_fraction(const ShadowLight& light, const glm::dvec3& p,
                                        const Triangle& t) {
  const SunDiskFrame frame = sun_disk_frame(light, "single_triangle_visible_fraction");
  // Always the homogeneous clip (unlike the exact oracle's projected vertices), so the two share
  // as little as possible.
  const DiskPolygon projection =
      project_triangle(frame, p, {glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)},
                       FrontProjection::clipped, 2.0);
  if (projection.count == 0) return 1.0;
  return std::clamp(1.0 - unit_disk_intersection_area(projection) / std::numbers::pi, 0.0, 1.0);
}

}  // namespace shadowcts
