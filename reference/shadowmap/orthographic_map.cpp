#include "reference/shadowmap/orthographic_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace shadowcts::shadowmap {

LightView orthographic_view(const glm::dvec3& towards_light, const ViewSamples& samples,
                            std::uint32_t resolution) {
  LightView view;
  view.perspective = false;
  view.resolution = resolution;
  view.forward = -glm::normalize(towards_light);
  // Any axis not parallel to forward gives an orthonormal frame.
  const glm::dvec3 helper =
      std::fabs(view.forward.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
  view.right = glm::normalize(glm::cross(helper, view.forward));
  view.up = glm::cross(view.forward, view.right);

  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  view.origin = glm::dvec3(0.0);
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const glm::dvec3 v = view.to_view(glm::dvec3(s.position));
    lo[0] = std::min(lo[0], v.x), hi[0] = std::max(hi[0], v.x);
    lo[1] = std::min(lo[1], v.y), hi[1] = std::max(hi[1], v.y);
  }
  if (!(lo[0] <= hi[0])) {  // no regular sample: any window will do
    view.half_extent = 1.0;
    return view;
  }
  const double centre_x = 0.5 * (lo[0] + hi[0]), centre_y = 0.5 * (lo[1] + hi[1]);
  double half = 0.5 * std::max(hi[0] - lo[0], hi[1] - lo[1]);
  half = std::max(half, 1e-6 * std::max(std::fabs(centre_x), std::fabs(centre_y)) + 1e-30);
  view.half_extent = half * (1.0 + 2.0 / double(resolution)) * (1.0 + 1e-9);
  view.origin = centre_x * view.right + centre_y * view.up;
  return view;
}

}  // namespace shadowcts::shadowmap
